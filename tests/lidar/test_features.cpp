#include <gtest/gtest.h>

#include <algorithm>

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

// The room's faces are axis-aligned in W: a surface normal seen in W lies within max_deg of an axis.
bool along_an_axis(const Vec3& n_W, double max_deg) {
  return n_W.cwiseAbs().maxCoeff() > std::cos(max_deg * M_PI / 180.0);
}

TEST(Features, RingSurfacesTakeTheirFacesNormalFromTheNeighbouringRings) {
  const test::Scene scene = test::box_room();
  // Tilted and noisy (2 cm, the oblique footprint), so that the normals are neither the sensor's axes nor exact.
  const SE3 T_W_L(Quat(Eigen::AngleAxisd(0.2, Vec3(1, 2, 0).normalized())), Vec3(0.5, -1.0, 0.3));
  const LidarScan scan = test::sweep(scene, [T_W_L](TimeNs) { return T_W_L; }, 0, 0.1, 0.2, 0.02, 0.003);
  FeatureConfig config;
  EXPECT_TRUE(extract_features(scan, RingConfig{}, config).surfaces.front().normal_L.isZero());  // not asked for
  config.ring_normals = true;
  const FeatureScan f = extract_features(scan, RingConfig{}, config);
  int with_normal = 0, on_the_face = 0;
  for (const FeaturePoint& s : f.surfaces) {
    if (s.normal_L.isZero()) continue;
    ++with_normal;
    ASSERT_NEAR(s.normal_L.norm(), 1.0, 1e-9);
    on_the_face += along_an_axis(T_W_L.rotation() * s.normal_L, 10.0);
  }
  for (const FeaturePoint& e : f.edges) EXPECT_TRUE(e.normal_L.isZero());
  // Nearly every surface point has a normal, and nearly every normal is its face's (within the 10 deg of the
  // registration's normal test), also next to the creases and the blocks' edges.
  EXPECT_GT(with_normal, 0.9 * f.surfaces.size()) << f.surfaces.size() << " surfaces";
  EXPECT_GT(on_the_face, 0.99 * with_normal) << with_normal << " normals";

  // Ring numbers that do not follow elevation (interleaved lasers) give the same normals: neighbours are found
  // by elevation.
  LidarScan interleaved = scan;
  for (LidarPoint& p : interleaved.points) p.ring = static_cast<std::uint16_t>((p.ring * 5) % 16);
  const FeatureScan g = extract_features(interleaved, RingConfig{}, config);
  ASSERT_EQ(g.surfaces.size(), f.surfaces.size());
  const auto by_position = [](const FeaturePoint& a, const FeaturePoint& b) {
    return std::lexicographical_compare(a.p_L.data(), a.p_L.data() + 3, b.p_L.data(), b.p_L.data() + 3);
  };
  std::vector<FeaturePoint> fs = f.surfaces, gs = g.surfaces;
  std::sort(fs.begin(), fs.end(), by_position);
  std::sort(gs.begin(), gs.end(), by_position);
  for (std::size_t i = 0; i < fs.size(); ++i) {
    ASSERT_EQ(gs[i].p_L, fs[i].p_L);
    EXPECT_EQ(gs[i].normal_L, fs[i].normal_L) << fs[i].p_L.transpose();
  }
}

TEST(Features, RejectsSurfacesNearlyParallelToTheBeam) {
  // In a 4 m wide corridor the side walls are swept at ever more grazing angles down its length.
  const test::Scene corridor{{Vec3(-500, -2, -1.5), Vec3(500, 2, 2)}, {}};
  RingConfig rings;
  rings.max_range_m = 60.0;
  const LidarScan scan = static_sweep(corridor, SE3());
  // Angle between the beam and the side wall's normal (y axis), seen from above, in degrees.
  const auto grazing_deg = [](const Vec3& p) { return std::acos(std::abs(p.y()) / p.head<2>().norm()) * 180 / M_PI; };
  const auto on_side_wall = [](const Vec3& p) { return std::abs(std::abs(p.y()) - 2.0) < 1e-3; };
  int steep = 0;
  for (const LidarPoint& q : scan.points) {
    const Vec3 p(q.x, q.y, q.z);
    steep += on_side_wall(p) && p.norm() < rings.max_range_m && grazing_deg(p) > 85.0;
  }
  ASSERT_GT(steep, 100);  // the sweep does contain such points
  const FeatureScan f = extract_features(scan, rings, FeatureConfig{});
  int on_walls = 0;
  for (const FeaturePoint& s : f.surfaces) {
    if (!on_side_wall(s.p_L)) continue;
    ++on_walls;
    // Neighbour gaps exceed 2 % of the range beyond about 80 deg for a 0.2 deg azimuth step.
    EXPECT_LT(grazing_deg(s.p_L), 81.0) << s.p_L.transpose();
  }
  EXPECT_GT(on_walls, 50);
}

TEST(Features, RangeNoiseOnNearbyWallsGivesNoEdges) {
  // A 2 m wide corridor, 2 cm range noise: within ~3 m of the sensor the noise alone makes LOAM's smoothness
  // exceed 0.02 on the flat walls; those noise "edges" sit where the walls are nearest, a sensor-fixed column
  // that registration then holds on to. Only the corner lines (and the far ends) are edges.
  const test::Scene corridor{{Vec3(-60, -1, -1.2), Vec3(40, 1, 1.8)}, {}};
  const LidarScan scan = test::sweep(corridor, [](TimeNs) { return SE3(); }, 0, 0.1, 0.2, 0.02);
  const FeatureScan f = extract_features(scan, RingConfig{}, FeatureConfig{});
  int on_walls = 0, on_near_corners = 0;
  for (const FeaturePoint& e : f.edges) {
    const double d = test::distance_to_scene_edges(corridor, e.p_L);
    on_walls += d >= 0.1;
    on_near_corners += d < 0.1 && e.p_L.norm() < 10.0;
  }
  EXPECT_LE(on_walls, 2);  // with the smoothness threshold alone: 1193 of 1243 edges
  EXPECT_GT(on_near_corners, 20);
}

// Down a corridor the side walls are swept at ever more grazing angles, where a real beam's footprint
// spreads the range (3 mrad: 4 cm at 10 m and 80 deg). The edge test counts that spread as noise; without it
// the spread makes noise "edges" all along the walls, which hide the corridor's degeneracy
// (LidarMapper.KeepsThePriorAlongTheLoopCorridor with the simulator's return model). The floor and ceiling
// keep some: their incidence is read along the ring, which runs across a downward beam (features.cpp).
TEST(Features, ObliqueFootprintSpreadGivesNoEdgesOnTheWalls) {
  const test::Scene corridor{{Vec3(-60, -1, -1.2), Vec3(40, 1, 1.8)}, {}};
  const LidarScan scan = test::sweep(corridor, [](TimeNs) { return SE3(); }, 0, 0.1, 0.2, 0.02, 0.003);
  const auto noise_edges = [&](const FeatureConfig& config) {
    std::pair<int, int> walls_and_rest{0, 0};
    for (const FeaturePoint& e : extract_features(scan, RingConfig{}, config).edges) {
      if (test::distance_to_scene_edges(corridor, e.p_L) < 0.1) continue;
      (std::abs(e.p_L.y()) > 0.9 ? walls_and_rest.first : walls_and_rest.second) += 1;
    }
    return walls_and_rest;
  };
  FeatureConfig spread_ignored;
  spread_ignored.beam_divergence_rad = 0.0;
  const auto [walls, rest] = noise_edges(FeatureConfig{});
  const auto [walls_ignored, rest_ignored] = noise_edges(spread_ignored);
  std::printf("[features] noise edges on the walls / floor and ceiling: %d / %d with the footprint spread counted, "
              "%d / %d without\n", walls, rest, walls_ignored, rest_ignored);
  EXPECT_LE(walls, 5);
  EXPECT_GT(walls_ignored, 10 * std::max(walls, 5));
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
