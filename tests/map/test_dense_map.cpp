// DenseMap: voxel indexing, running means, min hits, deterministic order, bad sizes.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>

#include "map/dense_map.h"

namespace vilslam::map {
namespace {

using Eigen::Vector3f;

TEST(DenseMap, PointsInOneVoxelAverage) {
  DenseMap map(0.01);
  EXPECT_EQ(map.insert({Vector3f(0.101f, 0.202f, 0.303f), Vector3f(0.107f, 0.208f, 0.309f)}), 2u);
  ASSERT_EQ(map.num_voxels(), 1u);
  const auto points = map.points();
  ASSERT_EQ(points.size(), 1u);
  EXPECT_NEAR(points[0].x(), 0.104f, 1e-6f);
  EXPECT_NEAR(points[0].y(), 0.205f, 1e-6f);
  EXPECT_NEAR(points[0].z(), 0.306f, 1e-6f);
}

TEST(DenseMap, NegativeCoordinatesIndexByFloor) {
  DenseMap map(0.01);
  // -0.001 and +0.001 straddle 0: two voxels (truncation toward zero would merge them).
  map.insert({Vector3f(-0.001f, 0.5f, 0.5f), Vector3f(0.001f, 0.5f, 0.5f)});
  EXPECT_EQ(map.num_voxels(), 2u);
  // -0.011 and -0.019 share voxel -2; -0.009 is in voxel -1.
  DenseMap negative(0.01);
  negative.insert({Vector3f(-0.011f, -0.011f, -0.011f), Vector3f(-0.019f, -0.019f, -0.019f),
                   Vector3f(-0.009f, -0.009f, -0.009f)});
  EXPECT_EQ(negative.num_voxels(), 2u);
  const auto points = negative.points();
  ASSERT_EQ(points.size(), 2u);
  EXPECT_NEAR(points[0].x(), -0.015f, 1e-6f);  // key order: voxel -2 before voxel -1
  EXPECT_NEAR(points[1].x(), -0.009f, 1e-6f);
}

TEST(DenseMap, OrderIsSortedByVoxelAndIndependentOfInsertion) {
  std::vector<Vector3f> points;
  for (int i = 0; i < 500; ++i) {
    const float a = static_cast<float>(i);
    points.emplace_back(std::sin(a) * 3.0f, std::cos(a * 1.7f) * 2.0f, std::sin(a * 0.3f) - 0.5f);
  }
  DenseMap forward(0.05), backward(0.05);
  forward.insert(points);
  backward.insert(std::vector<Vector3f>(points.rbegin(), points.rend()));
  const auto a = forward.points(), b = backward.points();
  ASSERT_EQ(a.size(), b.size());
  ASSERT_GT(a.size(), 100u);
  for (std::size_t i = 0; i < a.size(); ++i) EXPECT_TRUE(a[i].isApprox(b[i], 1e-5f)) << i;
  // Increasing (x, y, z) voxel index order.
  for (std::size_t i = 1; i < a.size(); ++i) {
    const Eigen::Vector3f prev = (a[i - 1] / 0.05f).array().floor(), cur = (a[i] / 0.05f).array().floor();
    EXPECT_TRUE(std::lexicographical_compare(prev.data(), prev.data() + 3, cur.data(), cur.data() + 3)) << i;
  }
}

TEST(DenseMap, MinHitsDropsSingleHits) {
  DenseMap map(0.1);
  map.insert({Vector3f(0.01f, 0.01f, 0.01f), Vector3f(0.02f, 0.02f, 0.02f), Vector3f(5.0f, 5.0f, 5.0f)});
  EXPECT_EQ(map.points(1).size(), 2u);
  ASSERT_EQ(map.points(2).size(), 1u);
  EXPECT_NEAR(map.points(2)[0].x(), 0.015f, 1e-6f);
  EXPECT_TRUE(map.points(3).empty());
}

TEST(DenseMap, SkipsNonFiniteAndOutOfRangePoints) {
  DenseMap map(0.01);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  EXPECT_EQ(map.insert({Vector3f(nan, 0, 0), Vector3f(0, std::numeric_limits<float>::infinity(), 0),
                        Vector3f(1e5f, 0, 0), Vector3f(1, 2, 3)}),
            1u);
  EXPECT_EQ(map.num_voxels(), 1u);
  EXPECT_EQ(map.num_points_inserted(), 1u);
}

TEST(DenseMap, MemoryFollowsOccupiedVoxels) {
  DenseMap map(0.01);
  const std::size_t empty_bytes = map.memory_bytes();
  std::vector<Vector3f> points;
  for (int i = 0; i < 20000; ++i) points.emplace_back(0.01f * static_cast<float>(i) + 0.005f, 0.005f, 0.005f);
  map.insert(points);
  EXPECT_EQ(map.num_voxels(), 20000u);
  const double bytes_per_voxel = static_cast<double>(map.memory_bytes() - empty_bytes) / 20000.0;
  EXPECT_GT(bytes_per_voxel, 16.0);
  EXPECT_LT(bytes_per_voxel, 128.0);
  // The same points again add hits, not voxels or memory.
  const std::size_t bytes = map.memory_bytes();
  map.insert(points);
  EXPECT_EQ(map.num_voxels(), 20000u);
  EXPECT_EQ(map.memory_bytes(), bytes);
}

TEST(DenseMap, RejectsBadVoxelSize) {
  EXPECT_THROW((void)DenseMap(0.0), std::invalid_argument);
  EXPECT_THROW((void)DenseMap(-0.01), std::invalid_argument);
  EXPECT_THROW((void)DenseMap(std::numeric_limits<double>::quiet_NaN()), std::invalid_argument);
  EXPECT_THROW((void)DenseMap(std::numeric_limits<double>::infinity()), std::invalid_argument);
}

}  // namespace
}  // namespace vilslam::map
