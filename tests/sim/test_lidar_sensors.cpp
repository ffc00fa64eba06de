#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "sim/lidar_beams.h"
#include "sim/lidar_sim.h"
#include "sim/world.h"

namespace vilslam::sim {
namespace {

double elevation_deg(const LidarPoint& p) { return std::atan2(p.z, std::hypot(p.x, p.y)) * 180.0 / M_PI; }

// Direction cells of 0.25 x 0.25 deg hit by the scan's points (centred on multiples of 0.25 deg, so that
// no VLP-16 beam direction falls on a cell border).
std::set<std::pair<int, int>> direction_cells(const LidarScan& scan) {
  std::set<std::pair<int, int>> cells;
  for (const LidarPoint& p : scan.points) {
    cells.emplace(static_cast<int>(std::lround(std::atan2(p.y, p.x) * 180.0 / M_PI * 4.0)),
                  static_cast<int>(std::lround(elevation_deg(p) * 4.0)));
  }
  return cells;
}

TEST(LidarSensors, Hesai128HasDenseBeamsAroundTheHorizonAndTheirRings) {
  const LidarSimConfig config = lidar_sensor("hesai128");
  ASSERT_EQ(config.num_rings, 128);
  const auto spacing_deg = [&](int ring) {
    return (ring_elevation_rad(config, ring + 1) - ring_elevation_rad(config, ring)) * 180.0 / M_PI;
  };
  EXPECT_NEAR(spacing_deg(0), 0.5, 1e-9);     // -24.5 deg
  EXPECT_NEAR(spacing_deg(60), 0.125, 1e-9);  // near the horizon
  EXPECT_NEAR(spacing_deg(126), 0.5, 1e-9);   // +15 deg
  const World world = World::generate(Scenario::kHallway, 1);
  const SE3 pose(Quat::Identity(), world.route_W()[5]);
  const LidarScan scan = simulate_sweep(world, config, 0, [&](TimeNs) { return pose; }, 1);
  EXPECT_TRUE(scan.has_ring);
  EXPECT_GT(scan.points.size(), 0.9 * 128 * 1800);
  std::set<int> rings;
  for (const LidarPoint& p : scan.points) {
    EXPECT_NEAR(elevation_deg(p) * M_PI / 180.0, ring_elevation_rad(config, p.ring), 0.002);
    rings.insert(p.ring);
  }
  EXPECT_EQ(rings.size(), 128u);
}

TEST(LidarSensors, Mid360HasNoRingsAndNeverRepeatsItsPattern) {
  const LidarSimConfig config = lidar_sensor("mid360");
  const World world = World::generate(Scenario::kHallway, 1);
  const SE3 pose(Quat::Identity(), world.route_W()[5]);
  const auto still = [&](TimeNs) { return pose; };
  const TimeNs period_ns = s_to_ns(1.0 / config.rate_hz);
  const LidarScan first = simulate_sweep(world, config, 3'000'000'000, still, 1);
  const LidarScan second = simulate_sweep(world, config, 3'000'000'000 + period_ns, still, 2);
  EXPECT_FALSE(first.has_ring);
  // 200,000 points/s at 10 Hz, nearly all returned inside a closed corridor.
  EXPECT_GT(first.points.size(), 0.95 * 20000);
  EXPECT_LE(first.points.size(), 20000u);
  float last_t = -1;
  for (const LidarPoint& p : first.points) {
    EXPECT_GE(elevation_deg(p), -7.0 - 1e-3);
    EXPECT_LE(elevation_deg(p), 52.0 + 1e-3);
    EXPECT_EQ(p.ring, 0);
    EXPECT_GE(p.t_offset_s, last_t);  // points in firing order, each at its own instant
    EXPECT_LT(p.t_offset_s, 0.1f);
    last_t = p.t_offset_s;
  }
  // Every sweep covers the whole circle; a second sweep adds directions the first missed, where a
  // spinning sensor repeats its own.
  std::set<int> azimuth_sectors;
  for (const LidarPoint& p : first.points) {
    azimuth_sectors.insert(std::min(35, static_cast<int>((std::atan2(p.y, p.x) + M_PI) / (2 * M_PI) * 36)));
  }
  EXPECT_EQ(azimuth_sectors.size(), 36u);
  auto both = direction_cells(first);
  const auto cells_second = direction_cells(second);
  both.insert(cells_second.begin(), cells_second.end());
  EXPECT_GT(both.size(), 1.6 * direction_cells(first).size());
  const LidarSimConfig vlp16 = lidar_sensor("vlp16");
  auto spinning = direction_cells(simulate_sweep(world, vlp16, 0, still, 1));
  const std::size_t one = spinning.size();
  const auto spinning_second = direction_cells(simulate_sweep(world, vlp16, period_ns, still, 2));
  spinning.insert(spinning_second.begin(), spinning_second.end());
  EXPECT_LT(spinning.size(), 1.01 * one);
}

// The geometry of the pattern: an ideal return model (mixed pixels lie on no surface, oblique footprints
// spread beyond the range noise; LidarReturns.* tests those).
TEST(LidarSensors, Mid360PointsLieOnSurfacesAtTheirOwnInstant) {
  LidarSimConfig config = lidar_sensor("mid360");
  config.returns = ideal_returns();
  const World world = World::generate(Scenario::kHighbay, 1);
  const Vec3 start_W = world.route_W()[20];
  const auto T_W_L = [start_W](TimeNs t_ns) {
    const double t = ns_to_s(t_ns);
    return SE3(Quat(Eigen::AngleAxisd(M_PI / 2 * t, Vec3::UnitZ())), start_W + Vec3(3.0 * t, 1.0 * t, 0.0));
  };
  const LidarScan scan = simulate_sweep(world, config, 0, T_W_L, 5);
  ASSERT_GT(scan.points.size(), 10000u);
  int within = 0;
  for (const LidarPoint& p : scan.points) {
    within += world.distance_to_surface(T_W_L(s_to_ns(p.t_offset_s)) * Vec3(p.x, p.y, p.z)) <= 3 * config.range_noise_sigma_m;
  }
  EXPECT_GT(within, 0.995 * scan.points.size());
}

TEST(LidarSensors, UnknownModelIsRejected) { EXPECT_THROW(lidar_sensor("hdl64"), std::invalid_argument); }

}  // namespace
}  // namespace vilslam::sim
