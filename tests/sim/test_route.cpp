// Another route through the same world (sim/route.h, varied_route): started part of the way round and shifted
// sideways, a closed route that keeps its distance from the original and starts where the fraction says.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "sim/route.h"

namespace vilslam::sim {
namespace {

// Distance from p to the polyline's segments.
double distance_to(const std::vector<Vec3>& polyline, const Vec3& p) {
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 1; i < polyline.size(); ++i) {
    const Vec3 a = polyline[i - 1], ab = polyline[i] - a;
    const double t = std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
    best = std::min(best, (a + t * ab - p).norm());
  }
  return best;
}

// The point s metres along the polyline.
Vec3 point_along(const std::vector<Vec3>& polyline, double s) {
  for (std::size_t i = 1; i < polyline.size(); ++i) {
    const double len = (polyline[i] - polyline[i - 1]).norm();
    if (s <= len) return polyline[i - 1] + (s / len) * (polyline[i] - polyline[i - 1]);
    s -= len;
  }
  return polyline.back();
}

TEST(VariedRoute, StartsPartWayRoundAndKeepsItsSideways) {
  // A counter-clockwise 10 m square with rounded corners: left of travel is inside.
  const std::vector<Vec3> route = rounded_loop({{0, 0}, {10, 0}, {10, 10}, {0, 10}}, 1.5, 0.5, 1.2);
  EXPECT_EQ(varied_route(route, 0.0, 0.0), route);
  const double length = polyline_length(route);
  const std::vector<Vec3> varied = varied_route(route, 0.25, 0.4);
  EXPECT_EQ(varied.front(), varied.back());
  // Inside by 0.4 m everywhere: shorter by 2 pi 0.4 (a closed convex curve), each waypoint 0.4 m from the route.
  EXPECT_NEAR(polyline_length(varied), length - 2.0 * M_PI * 0.4, 0.02 * length);
  for (const Vec3& p : varied) {
    EXPECT_NEAR(distance_to(route, p), 0.4, 0.03);
    EXPECT_DOUBLE_EQ(p.z(), 1.2);
  }
  // It starts beside the point a quarter of the way along the original route.
  EXPECT_NEAR((varied.front() - point_along(route, 0.25 * length)).norm(), 0.4, 0.1);
  // Shifted the other way: outside, longer.
  EXPECT_GT(polyline_length(varied_route(route, 0.0, -0.4)), length);
}

}  // namespace
}  // namespace vilslam::sim
