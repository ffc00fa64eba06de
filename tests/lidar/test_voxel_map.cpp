#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "lidar/voxel_map.h"

namespace vilslam::lidar {
namespace {

std::vector<Vec3> random_points(std::size_t n, double extent, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-extent, extent);
  std::vector<Vec3> points;
  for (std::size_t i = 0; i < n; ++i) points.emplace_back(u(rng), u(rng), u(rng));
  return points;
}

TEST(VoxelMap, NearestMatchesBruteForce) {
  VoxelMapConfig config;
  config.voxel_size_m = 1.0;
  config.min_point_spacing_m = 0.0;
  config.max_points_per_voxel = 1000;
  VoxelMap map(config);
  const std::vector<Vec3> points = random_points(20000, 10.0, 1);
  map.insert(points);
  ASSERT_EQ(map.num_points(), points.size());
  for (const Vec3& q : random_points(300, 10.0, 2)) {
    std::vector<double> d;
    for (const Vec3& p : points) {
      if ((p - q).norm() <= 0.8) d.push_back((p - q).norm());
    }
    std::sort(d.begin(), d.end());
    const std::vector<Vec3> found = map.nearest(q, 5, 0.8);
    ASSERT_EQ(found.size(), std::min<std::size_t>(5, d.size()));
    for (std::size_t i = 0; i < found.size(); ++i) EXPECT_DOUBLE_EQ((found[i] - q).norm(), d[i]);
  }
}

TEST(VoxelMap, DownsamplesCapsAndForgetsFarVoxels) {
  VoxelMapConfig config;
  config.voxel_size_m = 1.0;
  config.min_point_spacing_m = 0.3;
  config.max_points_per_voxel = 4;
  config.max_distance_m = 5.0;
  VoxelMap map(config);
  map.insert({Vec3(0.1, 0.1, 0.1), Vec3(0.2, 0.1, 0.1), Vec3(0.9, 0.1, 0.1)});
  EXPECT_EQ(map.num_points(), 2u);  // the second point is within 0.3 m of the first
  map.insert(random_points(1000, 20.0, 3));
  for (const Vec3& p : map.points()) EXPECT_TRUE(p.allFinite());
  EXPECT_LE(map.num_points(), 4 * map.num_voxels());
  map.remove_far(Vec3(10, 10, 10));
  ASSERT_GT(map.num_voxels(), 0u);
  for (const Vec3& p : map.points()) EXPECT_LT((p - Vec3(10, 10, 10)).norm(), 5.0 + std::sqrt(3.0));
}

TEST(VoxelMap, DownsampleKeepsFirstPointPerLeaf) {
  const std::vector<Vec3> kept = voxel_downsample({Vec3(0.05, 0, 0), Vec3(0.1, 0, 0), Vec3(0.3, 0, 0)}, 0.2);
  ASSERT_EQ(kept.size(), 2u);
  EXPECT_EQ(kept[0], Vec3(0.05, 0, 0));
  EXPECT_EQ(kept[1], Vec3(0.3, 0, 0));
}

}  // namespace
}  // namespace vilslam::lidar
