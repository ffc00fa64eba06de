// Line and plane fits of map neighbours: a plane needs neighbours spread over two axes.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "lidar/correspondences.h"
#include "lidar/voxel_map.h"

namespace vilslam::lidar {
namespace {

// Points along one LiDAR ring on the floor z = 0 (x from 0 to 0.4 m) with 2 cm range noise across it.
std::vector<Vec3> ring_points(std::mt19937& rng) {
  std::normal_distribution<double> noise(0.0, 0.02);
  std::vector<Vec3> p;
  for (int i = 0; i < 5; ++i) p.emplace_back(0.1 * i, noise(rng), noise(rng));
  return p;
}

TEST(FitPlane, RejectsNeighboursAlongOneRingWhenSpreadIsRequired) {
  std::mt19937 rng(3);
  const std::vector<Vec3> ring = ring_points(rng);
  // Without the spread test the noise across the ring decides the tilt: the normal is far from z.
  const std::optional<Plane> loose = fit_plane(ring, 0.2, 0.0);
  ASSERT_TRUE(loose.has_value());
  EXPECT_LT(std::abs(loose->normal.z()), 0.99);
  EXPECT_FALSE(fit_plane(ring, 0.2, 0.1).has_value());
}

TEST(FitPlane, KeepsAPatchSpreadOverTwoRings) {
  std::mt19937 rng(3);
  std::normal_distribution<double> noise(0.0, 0.005);
  std::vector<Vec3> patch;
  for (int ring = 0; ring < 2; ++ring) {
    for (int i = 0; i < 3; ++i) patch.emplace_back(0.1 * i, 0.2 * ring, noise(rng));
  }
  const std::optional<Plane> plane = fit_plane(patch, 0.2, 0.1);
  ASSERT_TRUE(plane.has_value());
  EXPECT_GT(std::abs(plane->normal.z()), 0.99);
}

// A tunnel's arch overhead (a cylinder of radius 2.5 m about the x axis): a query on the surface of its own ring
// (x = 0), map neighbours three points of that ring 0.2 m apart and two of the next ring (x = 0.1 m). The arc's
// points bulge away from their chord, so the plane through the neighbours' centroid lies inside the arch and
// misses every query on it to the same side (4.8 mm here); the plane through the nearest neighbour, with the
// same normal, passes within 0.5 mm.
TEST(AssociatePlane, ThroughTheNearestNeighbourItFollowsACurvedSurface) {
  constexpr double kRadius = 2.5;
  const auto on_arch = [](double x_m, double angle_rad) {
    return Vec3(x_m, kRadius * std::sin(angle_rad), kRadius * std::cos(angle_rad));
  };
  VoxelMapConfig map_config;
  map_config.min_point_spacing_m = 0.01;
  VoxelMap map(map_config);
  map.insert({on_arch(0, -0.08), on_arch(0, 0), on_arch(0, 0.08), on_arch(0.1, -0.04), on_arch(0.1, 0.04)});
  const Vec3 query = on_arch(0, 0.02);
  AssociationConfig config;
  config.min_plane_spread_ratio = 0.1;
  const auto residual_m = [&](bool through_nearest) {
    config.plane_through_nearest = through_nearest;
    const std::optional<PlaneCorrespondence> c = associate_plane(query, query, map, config);
    EXPECT_TRUE(c.has_value());
    return c ? c->normal_W.dot(query) + c->offset_m : 0.0;
  };
  EXPECT_GT(std::abs(residual_m(false)), 0.004);
  EXPECT_LT(std::abs(residual_m(true)), 0.001);
}

// A corridor's ceiling (z = 0) meets its wall (x = 0) in a concave crease. A ceiling query 0.1 m from the wall
// finds three ceiling and two wall neighbours (those 10 cm below the crease); their plane cuts the corner, over 10 deg
// off the ceiling and below it. Matched to it, the query pulls the sensor towards the floor. With the query's own
// normal (up), the plane fails the normal test; a query of unknown normal keeps the old behaviour.
TEST(AssociatePlane, TheNormalTestRejectsAPlaneAcrossACrease) {
  VoxelMapConfig map_config;
  map_config.min_point_spacing_m = 0.01;
  VoxelMap map(map_config);
  map.insert({Vec3(0.25, 0.3, 0), Vec3(0.25, 0.7, 0), Vec3(0.45, 0.5, 0), Vec3(0, 0.4, -0.1), Vec3(0, 0.6, -0.1)});
  const Vec3 query(0.1, 0.5, 0);
  const Vec3 up = Vec3::UnitZ();
  AssociationConfig config;
  const std::optional<PlaneCorrespondence> crease = associate_plane(query, query, map, config, up);
  ASSERT_TRUE(crease.has_value());
  const double tilt_deg = std::acos(std::abs(crease->normal_W.z())) * 180.0 / M_PI;
  EXPECT_GT(tilt_deg, 10.0);
  EXPECT_GT(std::abs(crease->normal_W.dot(query) + crease->offset_m), 0.005);  // the query misses the plane
  config.max_normal_angle_deg = 10.0;
  EXPECT_FALSE(associate_plane(query, query, map, config, up).has_value());
  EXPECT_TRUE(associate_plane(query, query, map, config, Vec3::Zero()).has_value());
  // Away from the crease the same test keeps the ceiling's own plane.
  VoxelMap ceiling(map_config);
  ceiling.insert({Vec3(0.25, 0.3, 0), Vec3(0.25, 0.7, 0), Vec3(0.45, 0.5, 0), Vec3(0.45, 0.3, 0), Vec3(0.45, 0.7, 0)});
  EXPECT_TRUE(associate_plane(query, query, ceiling, config, up).has_value());
}

TEST(FitLine, NeedsAnElongatedScatter) {
  std::mt19937 rng(3);
  const std::optional<Line> line = fit_line(ring_points(rng), 3.0);
  ASSERT_TRUE(line.has_value());
  EXPECT_GT(std::abs(line->direction.x()), 0.99);
  const std::vector<Vec3> blob{{0, 0, 0}, {0.1, 0, 0}, {0, 0.1, 0}, {0.1, 0.1, 0}};
  EXPECT_FALSE(fit_line(blob, 3.0).has_value());
}

}  // namespace
}  // namespace vilslam::lidar
