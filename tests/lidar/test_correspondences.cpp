// Line and plane fits of map neighbours: a plane needs neighbours spread over two axes.
#include <gtest/gtest.h>

#include <random>

#include "lidar/correspondences.h"

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
