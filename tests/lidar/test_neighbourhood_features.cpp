#include <gtest/gtest.h>

#include <cmath>

#include "lidar/features.h"
#include "synthetic_scene.h"

namespace vilslam::lidar {
namespace {

TEST(NeighbourhoodFeatures, AutoChoosesRingsOnlyWhereTheScanHasThem) {
  const test::Scene scene = test::box_room();
  const SE3 T_W_L(Quat::Identity(), Vec3(0.5, -1.0, 0.0));
  LidarScan spinning = test::sweep(scene, [&](TimeNs) { return T_W_L; }, 0);
  EXPECT_EQ(resolve_feature_method(spinning, RingConfig{}, FeatureMethod::kAuto), FeatureMethod::kRings);
  // Without its ring field a spinning scan still falls on the configured rings.
  spinning.has_ring = false;
  EXPECT_GT(fraction_on_rings(spinning, RingConfig{}), 0.95);
  EXPECT_EQ(resolve_feature_method(spinning, RingConfig{}, FeatureMethod::kAuto), FeatureMethod::kRings);
  const LidarScan free = test::non_repetitive_sweep(scene, T_W_L);
  EXPECT_LT(fraction_on_rings(free, RingConfig{}), 0.7);
  EXPECT_EQ(resolve_feature_method(free, RingConfig{}, FeatureMethod::kAuto), FeatureMethod::kNeighbourhood);
  EXPECT_EQ(resolve_feature_method(free, RingConfig{}, FeatureMethod::kRings), FeatureMethod::kRings);
}

TEST(NeighbourhoodFeatures, EdgesOnBoxEdgesAndSurfacesOnFaces) {
  const test::Scene scene = test::box_room();
  const SE3 T_W_L(Quat::Identity(), Vec3(0.5, -1.0, 0.0));
  const LidarScan scan = test::non_repetitive_sweep(scene, T_W_L);
  const FeatureConfig config;
  const FeatureScan f = extract_features(scan, RingConfig{}, config);
  const NeighbourhoodFeatureConfig& n = config.neighbourhood;
  ASSERT_GT(f.edges.size(), 20u);
  ASSERT_GT(f.surfaces.size(), 500u);
  const std::size_t cells = static_cast<std::size_t>(n.azimuth_cells * n.elevation_cells);
  EXPECT_LE(f.edges.size(), cells * n.max_edges_per_cell);
  EXPECT_LE(f.surfaces.size(), cells * n.max_surfaces_per_cell);
  // An edge is a crease of the room or of a block: its neighbourhood (about two sample spacings of 1 deg)
  // reaches over it. A surface point is not on one (its neighbourhood lies on one face).
  int near_edges = 0, off_edges = 0;
  for (const FeaturePoint& e : f.edges) {
    near_edges += test::distance_to_scene_edges(scene, T_W_L * e.p_L) < std::max(0.15, 0.04 * e.p_L.norm());
  }
  for (const FeaturePoint& s : f.surfaces) off_edges += test::distance_to_scene_edges(scene, T_W_L * s.p_L) > 0.03;
  std::cout << near_edges << " of " << f.edges.size() << " edges near a crease, " << off_edges << " of "
            << f.surfaces.size() << " surfaces off the creases\n";
  EXPECT_GT(near_edges, 0.9 * f.edges.size());
  EXPECT_GT(off_edges, 0.99 * f.surfaces.size());
  // A surface's normal is its face's (the room's faces are axis-aligned): within 10 deg for nearly all of them.
  int along_an_axis = 0;
  for (const FeaturePoint& s : f.surfaces) {
    ASSERT_NEAR(s.normal_L.norm(), 1.0, 1e-6);
    along_an_axis += s.normal_L.cwiseAbs().maxCoeff() > std::cos(10.0 * M_PI / 180.0);
  }
  EXPECT_GT(along_an_axis, 0.98 * f.surfaces.size());
  for (const FeaturePoint& e : f.edges) EXPECT_TRUE(e.normal_L.isZero());
  // Deterministic, in scan order.
  const FeatureScan again = extract_features(scan, RingConfig{}, config);
  ASSERT_EQ(again.surfaces.size(), f.surfaces.size());
  for (std::size_t i = 0; i < f.surfaces.size(); ++i) EXPECT_EQ(again.surfaces[i].p_L, f.surfaces[i].p_L);
}

TEST(Features, MoreRingsThanTheReferenceTakeFewerPointsPerRing) {
  const test::Scene scene = test::box_room();
  const LidarScan scan = test::sweep(scene, [](TimeNs) { return SE3(Quat::Identity(), Vec3(0.5, -1.0, 0.0)); }, 0);
  FeatureConfig config;
  const FeatureScan all = extract_features(scan, RingConfig{}, config);
  config.reference_rings = 4;  // the 16 rings count as four times too many
  const FeatureScan quarter = extract_features(scan, RingConfig{}, config);
  EXPECT_LE(quarter.edges.size(), std::size_t(16 * config.sectors_per_ring * config.max_edges_per_sector / 4));
  EXPECT_LE(quarter.surfaces.size(), std::size_t(16 * config.sectors_per_ring * config.max_surfaces_per_sector / 4));
  EXPECT_LT(quarter.surfaces.size(), all.surfaces.size());
}

}  // namespace
}  // namespace vilslam::lidar
