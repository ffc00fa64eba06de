#include <gtest/gtest.h>

#include "lidar/features.h"
#include "synthetic_scene.h"

namespace vilslam::lidar {
namespace {

LidarScan static_sweep(const test::Scene& scene, const SE3& T_W_L) {
  return test::sweep(scene, [T_W_L](TimeNs) { return T_W_L; }, 0);
}

TEST(RingAssignment, ElevationGivesTheRingField) {
  const LidarScan with_ring = static_sweep(test::box_room(), SE3(Quat::Identity(), Vec3(0.5, -1.0, 0.0)));
  LidarScan without_ring = with_ring;
  without_ring.has_ring = false;
  for (LidarPoint& p : without_ring.points) p.ring = 0;
  const Rings a = assign_rings(with_ring, RingConfig{});
  const Rings b = assign_rings(without_ring, RingConfig{});
  ASSERT_EQ(a.size(), 16u);
  EXPECT_EQ(a, b);
  // Each ring is in azimuth order.
  for (const auto& ring : a) {
    for (std::size_t i = 1; i < ring.size(); ++i) {
      const LidarPoint& p = with_ring.points[ring[i - 1]];
      const LidarPoint& q = with_ring.points[ring[i]];
      EXPECT_LE(std::atan2(p.y, p.x), std::atan2(q.y, q.x));
    }
  }
}

TEST(Features, EdgesOnBoxEdgesAndSurfacesOnFaces) {
  const test::Scene scene = test::box_room();
  const SE3 T_W_L(Quat::Identity(), Vec3(0.5, -1.0, 0.0));
  FeatureConfig config;
  const FeatureScan f = extract_features(static_sweep(scene, T_W_L), RingConfig{}, config);
  ASSERT_GT(f.edges.size(), 30u);
  ASSERT_GT(f.surfaces.size(), 500u);
  EXPECT_LE(f.edges.size(), std::size_t(16 * config.sectors_per_ring * config.max_edges_per_sector));
  EXPECT_LE(f.surfaces.size(), std::size_t(16 * config.sectors_per_ring * config.max_surfaces_per_sector));
  int edges_on_blocks = 0;
  for (const FeaturePoint& e : f.edges) {
    const Vec3 p_W = T_W_L * e.p_L;
    // Points on the far side of an occluding block are no edges: every edge is on a real box edge.
    EXPECT_LT(test::distance_to_scene_edges(scene, p_W), 0.1) << p_W.transpose();
    for (const test::Box& b : scene.blocks) edges_on_blocks += test::distance_to_box_edges(b, p_W) < 0.1;
  }
  EXPECT_GT(edges_on_blocks, 10);
  // A level sensor's rings cross the vertical edges (horizontal ones run along the rings and may be flat
  // along them): no surface point sits on a vertical edge.
  for (const FeaturePoint& s : f.surfaces) {
    EXPECT_GT(test::distance_to_scene_edges(scene, T_W_L * s.p_L, true), 0.05) << (T_W_L * s.p_L).transpose();
  }
}

TEST(Features, CountsFollowTheConfig) {
  const LidarScan scan = static_sweep(test::box_room(), SE3());
  FeatureConfig config;
  config.max_edges_per_sector = 1;
  config.max_surfaces_per_sector = 3;
  config.sectors_per_ring = 4;
  const FeatureScan f = extract_features(scan, RingConfig{}, config);
  EXPECT_LE(f.edges.size(), 16u * 4u);
  EXPECT_GT(f.surfaces.size(), 16u * 4u * 2u);  // every sector of this room has flat points
  EXPECT_LE(f.surfaces.size(), 16u * 4u * 3u);
}

}  // namespace
}  // namespace vilslam::lidar
