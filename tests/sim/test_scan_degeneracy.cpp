#include <gtest/gtest.h>

#include <cmath>

#include "sim/scan_degeneracy.h"

namespace vilslam::sim {
namespace {

// The LiDAR pose at waypoint i, looking along the route.
SE3 route_pose(const World& world, std::size_t i) {
  const auto& r = world.route_W();
  const Vec3 d = r[i + 1] - r[i];
  return SE3(Quat(Eigen::AngleAxisd(std::atan2(d.y(), d.x()), Vec3::UnitZ())), r[i]);
}

TEST(ScanDegeneracy, TunnelIsDegenerateAlongItsAxisHighbayIsNot) {
  const LidarSimConfig config;
  const World tunnel = World::generate(Scenario::kTunnel, 1);
  const World highbay = World::generate(Scenario::kHighbay, 1);
  const std::size_t mid_t = tunnel.route_W().size() / 4, mid_h = highbay.route_W().size() / 4;
  const ScanDegeneracy t = analyze_scan_degeneracy(tunnel, config, route_pose(tunnel, mid_t));
  const ScanDegeneracy h = analyze_scan_degeneracy(highbay, config, route_pose(highbay, mid_h));
  ASSERT_GT(t.num_points, 20000);
  ASSERT_GT(h.num_points, 20000);
  // The tunnel axis is world x: the weakest direction is a translation along it.
  EXPECT_LT(t.min_max_ratio, 1e-6);
  EXPECT_GT(std::abs(t.weakest_direction(0)), 0.99);
  EXPECT_LT(t.weakest_direction.tail<3>().norm(), 0.1);
  EXPECT_GT(h.min_max_ratio, 1e-3);
  EXPECT_GT(h.min_max_ratio, 1000 * t.min_max_ratio);
  std::printf("tunnel ratio %.3g weakest %s\nhighbay ratio %.3g eigenvalues %s\n", t.min_max_ratio,
              ::testing::PrintToString(t.weakest_direction.transpose()).c_str(), h.min_max_ratio,
              ::testing::PrintToString(h.eigenvalues.transpose()).c_str());
  // The information matrix is symmetric positive semi-definite and its eigenvectors orthonormal.
  EXPECT_TRUE(h.information.isApprox(h.information.transpose()));
  EXPECT_GE(h.eigenvalues(0), 0.0);
  EXPECT_TRUE((h.eigenvectors.transpose() * h.eigenvectors).isApprox(Mat6::Identity(), 1e-9));
}

// Translation information along the direction of travel relative to across it.
double along_over_across(const World& world, std::size_t i) {
  const ScanDegeneracy d = analyze_scan_degeneracy(world, LidarSimConfig{}, route_pose(world, i));
  const Vec3 along = (world.route_W()[i + 1] - world.route_W()[i]).normalized();
  const Vec3 across = Vec3::UnitZ().cross(along);
  const Mat3 I_t = d.information.topLeftCorner<3, 3>();
  return along.dot(I_t * along) / across.dot(I_t * across);
}

TEST(ScanDegeneracy, HallwayIsWeakAlongTheCorridorHighbayIsNot) {
  const World hallway = World::generate(Scenario::kHallway, 1);
  const World highbay = World::generate(Scenario::kHighbay, 1);
  // The weakest place along each route (mid-way along a corridor leg in the hallway).
  auto weakest = [](const World& world) {
    double lowest = 1e9;
    for (std::size_t i = 0; i + 1 < world.route_W().size(); i += 8) lowest = std::min(lowest, along_over_across(world, i));
    return lowest;
  };
  const double corridor = weakest(hallway), hall = weakest(highbay);
  std::printf("along/across translation information: hallway %.3g highbay %.3g\n", corridor, hall);
  EXPECT_LT(corridor, 0.05);
  EXPECT_GT(hall, 0.2);
}

}  // namespace
}  // namespace vilslam::sim
