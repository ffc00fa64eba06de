#include <gtest/gtest.h>

#include <cmath>
#include <unordered_map>
#include <vector>

#include "sim/lidar_sim.h"
#include "sim/world.h"

namespace vilslam::sim {
namespace {

// Points of a cloud hashed into cubic cells, for nearest-point queries within one cell size.
class CellIndex {
 public:
  CellIndex(const PointCloud& cloud, double cell) : cell_(cell) {
    for (const auto& p : cloud.points) cells_[key(p.cast<double>())].push_back(p.cast<double>());
  }
  double nearest(const Vec3& p) const {
    double best = std::numeric_limits<double>::infinity();
    const Eigen::Vector3i c = (p / cell_).array().floor().cast<int>();
    for (int dx = -1; dx <= 1; ++dx) {
      for (int dy = -1; dy <= 1; ++dy) {
        for (int dz = -1; dz <= 1; ++dz) {
          const auto it = cells_.find(pack(c + Eigen::Vector3i(dx, dy, dz)));
          if (it == cells_.end()) continue;
          for (const Vec3& q : it->second) best = std::min(best, (q - p).norm());
        }
      }
    }
    return best;
  }

 private:
  static std::int64_t pack(const Eigen::Vector3i& c) {
    return (static_cast<std::int64_t>(c.x() + (1 << 20)) << 42) | (static_cast<std::int64_t>(c.y() + (1 << 20)) << 21) |
           static_cast<std::int64_t>(c.z() + (1 << 20));
  }
  std::int64_t key(const Vec3& p) const { return pack((p / cell_).array().floor().cast<int>()); }
  double cell_;
  std::unordered_map<std::int64_t, std::vector<Vec3>> cells_;
};

// What the LiDAR sees is in the reference model: hiding covered faces never removes a visible surface.
TEST(ReferenceModel, EverySurfaceTheLidarSeesIsSampled) {
  LidarSimConfig config;
  config.range_noise_sigma_m = 0;
  config.max_range_m = 40;
  for (const auto& [scenario, spacing] : std::vector<std::pair<Scenario, double>>{
           {Scenario::kHighbay, 0.05}, {Scenario::kHallway, 0.05}, {Scenario::kTunnel, 0.05},
           {Scenario::kRoom, 0.05}, {Scenario::kOutdoor, 0.1}}) {
    const World world = World::generate(scenario, 2);
    const CellIndex model(world.sample_surfaces(spacing), 2 * spacing);
    int far = 0, total = 0;
    for (const std::size_t i : {std::size_t{3}, world.route_W().size() / 2}) {
      const SE3 pose(Quat::Identity(), world.route_W()[i]);
      const LidarScan scan = simulate_sweep(world, config, 0, [&](TimeNs) { return pose; }, 0);
      for (std::size_t k = 0; k < scan.points.size(); k += 3) {
        const LidarPoint& p = scan.points[k];
        far += model.nearest(pose * Vec3(p.x, p.y, p.z)) > spacing;
        ++total;
      }
    }
    EXPECT_GT(total, 10000) << scenario_name(scenario);
    EXPECT_LT(far, 0.001 * total) << scenario_name(scenario) << ": " << far << " of " << total << " returns off the model";
  }
}

}  // namespace
}  // namespace vilslam::sim
