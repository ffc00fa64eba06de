#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "sim/rng.h"
#include "sim/shapes.h"
#include "sim/world.h"

namespace vilslam::sim {
namespace {

ShapeHit must_hit(const Shape& shape, const Vec3& origin, const Vec3& dir) {
  ShapeHit hit;
  EXPECT_TRUE(shape.intersect(Ray{origin, dir.normalized()}, 1e9, &hit)) << origin.transpose() << " -> " << dir.transpose();
  return hit;
}

TEST(Shapes, BoxHitsFromOutsideAndInside) {
  const Box box = Box::axis_aligned(Vec3(0, 0, 0), Vec3(1, 2, 3));
  ShapeHit h = must_hit(box, Vec3(-1, 1, 1.5), Vec3::UnitX());
  EXPECT_NEAR(h.t, 1.0, 1e-12);
  EXPECT_EQ(h.face, 0);
  EXPECT_TRUE(h.normal.isApprox(-Vec3::UnitX()));
  EXPECT_TRUE(h.uv.isApprox(Eigen::Vector2d(1.0, 1.5)));
  h = must_hit(box, Vec3(0.5, 1, 1.5), Vec3::UnitX());
  EXPECT_NEAR(h.t, 0.5, 1e-12);
  EXPECT_EQ(h.face, 1);
  h = must_hit(box, Vec3(0.25, 1, 10), -Vec3::UnitZ());
  EXPECT_NEAR(h.t, 7.0, 1e-12);
  EXPECT_EQ(h.face, 5);
  EXPECT_TRUE(h.uv.isApprox(Eigen::Vector2d(0.25, 1.0)));
  ShapeHit miss;
  EXPECT_FALSE(box.intersect(Ray{Vec3(-1, 3, 1), Vec3::UnitX()}, 1e9, &miss));
  EXPECT_FALSE(box.intersect(Ray{Vec3(-1, 1, 1), Vec3::UnitX()}, 0.9, &miss)) << "beyond t_max";
  EXPECT_FALSE(box.intersect(Ray{Vec3(2, 1, 1), Vec3::UnitX()}, 1e9, &miss)) << "behind the origin";
}

TEST(Shapes, OrientedBoxHitMatchesTheRotatedRectangle) {
  const Mat3 R = Eigen::AngleAxisd(M_PI / 4, Vec3::UnitZ()).toRotationMatrix();
  const Box box(Vec3::Zero(), R, Vec3(1, 0.5, 0.5));
  // Along world x the rotated rectangle spans |x| <= 0.5 / sin(45 deg); the hit is on the local +y face.
  const ShapeHit h = must_hit(box, Vec3(-5, 0, 0), Vec3::UnitX());
  EXPECT_NEAR(h.t, 5 - 0.5 / std::sin(M_PI / 4), 1e-12);
  EXPECT_EQ(h.face, 3);
  EXPECT_TRUE(h.normal.isApprox(Vec3(-std::sqrt(0.5), std::sqrt(0.5), 0)));
}

TEST(Shapes, CylinderSideAndCaps) {
  const Cylinder cyl(Eigen::Vector2d(2, 3), 0.0, 4.0, 0.5);
  ShapeHit h = must_hit(cyl, Vec3(0, 3, 1), Vec3::UnitX());
  EXPECT_NEAR(h.t, 1.5, 1e-12);
  EXPECT_EQ(h.face, 0);
  EXPECT_TRUE(h.normal.isApprox(-Vec3::UnitX()));
  EXPECT_NEAR(h.uv.y(), 1.0, 1e-12);
  EXPECT_NEAR(h.uv.x(), M_PI * 0.5, 1e-12);  // half way round from +x
  h = must_hit(cyl, Vec3(2.2, 3, 10), -Vec3::UnitZ());
  EXPECT_NEAR(h.t, 6.0, 1e-12);
  EXPECT_EQ(h.face, 2);
  h = must_hit(cyl, Vec3(2, 3, 2), Vec3(1, 0, 1));  // from inside, out through the side
  EXPECT_NEAR(h.t, 0.5 * std::sqrt(2.0), 1e-12);
}

TEST(Shapes, QuadHitsOnlyInsideItsRectangle) {
  const Quad wall(Vec3(0, 0, 0), Vec3::UnitX(), 4.0, Vec3::UnitZ(), 3.0);
  const ShapeHit h = must_hit(wall, Vec3(1, -2, 1), Vec3::UnitY());
  EXPECT_NEAR(h.t, 2.0, 1e-12);
  EXPECT_TRUE(h.uv.isApprox(Eigen::Vector2d(1, 1)));
  ShapeHit miss;
  EXPECT_FALSE(wall.intersect(Ray{Vec3(5, -2, 1), Vec3::UnitY()}, 1e9, &miss));
  EXPECT_FALSE(wall.intersect(Ray{Vec3(1, -2, 1), Vec3::UnitX()}, 1e9, &miss));
  EXPECT_NEAR(wall.distance(Vec3(5, 1, 1)), std::sqrt(2.0), 1e-12);
}

TEST(Shapes, ArchedTubeVaultFloorAndCaps) {
  const double r = 3, h = 1;
  const ArchedTube tube(Vec3(0, 0, h), 0.0, 100.0, r, h);
  const Vec3 axis_point(50, 0, h);
  ShapeHit hit = must_hit(tube, axis_point, Vec3::UnitZ());
  EXPECT_NEAR(hit.t, r, 1e-12);
  EXPECT_EQ(hit.face, 0);
  EXPECT_TRUE(hit.normal.isApprox(-Vec3::UnitZ()));
  EXPECT_NEAR(hit.uv.y(), r * (M_PI / 2 + std::asin(h / r)), 1e-9);
  hit = must_hit(tube, axis_point, Vec3::UnitY());
  EXPECT_NEAR(hit.t, r, 1e-12);
  EXPECT_NEAR(hit.uv.y(), r * (M_PI + std::asin(h / r)), 1e-9) << "arc length continuous past the +y side";
  hit = must_hit(tube, axis_point, -Vec3::UnitZ());
  EXPECT_NEAR(hit.t, h, 1e-12);
  EXPECT_EQ(hit.face, 1);
  hit = must_hit(tube, axis_point, Vec3::UnitX());
  EXPECT_NEAR(hit.t, 50, 1e-12);
  EXPECT_EQ(hit.face, 3);
  // A turned tube: yaw 90 degrees runs along +y.
  const ArchedTube turned(Vec3(0, 0, h), M_PI / 2, 10.0, r, h);
  hit = must_hit(turned, Vec3(0, 5, h), Vec3::UnitY());
  EXPECT_NEAR(hit.t, 5, 1e-9);
  EXPECT_EQ(hit.face, 3);
}

// Exact distances agree with the distance to a dense sampling of the surface (up to the sampling).
TEST(Shapes, DistanceMatchesDenseSurfaceSampling) {
  std::vector<std::unique_ptr<Shape>> shapes;
  shapes.push_back(std::make_unique<Box>(Vec3(0.2, -0.1, 0.5), Eigen::AngleAxisd(0.4, Vec3::UnitZ()).toRotationMatrix(),
                                         Vec3(0.8, 0.5, 0.4)));
  shapes.push_back(std::make_unique<Cylinder>(Eigen::Vector2d(0.1, 0.2), -0.5, 0.7, 0.6));
  shapes.push_back(std::make_unique<Quad>(Vec3(-1, -1, 0.2), Vec3(1, 0, 0.1), 1.8, Vec3(0, 1, 0), 1.5));
  shapes.push_back(std::make_unique<ArchedTube>(Vec3(-1, 0.1, 0.4), 0.3, 2.0, 1.0, 0.5));
  const double spacing = 0.01;
  Rng rng(3);
  for (const auto& shape : shapes) {
    std::vector<SurfacePoint> samples;
    shape->sample(spacing, &samples);
    ASSERT_GT(samples.size(), 1000u);
    for (const SurfacePoint& s : samples) {
      if (&s - samples.data() < 2000) {
        ASSERT_LT(shape->distance(s.p), 1e-9);
      }
    }
    for (int k = 0; k < 100; ++k) {
      const Vec3 p(rng.uniform(-1.8, 1.8), rng.uniform(-1.8, 1.8), rng.uniform(-1.5, 2.0));
      double brute = 1e9;
      for (const SurfacePoint& s : samples) brute = std::min(brute, (s.p - p).norm());
      const double exact = shape->distance(p);
      EXPECT_LE(exact, brute + 1e-9);
      EXPECT_GE(exact, brute - spacing) << "shape " << (&shape - shapes.data()) << " at " << p.transpose();
    }
  }
}

// In every world, sphere tracing with distance_to_surface reaches the surface where raycast hits it.
TEST(Shapes, WorldRaycastAgreesWithDistanceToSurface) {
  Rng rng(9);
  for (const Scenario s : {Scenario::kHighbay, Scenario::kHallway, Scenario::kTunnel, Scenario::kLoop,
                           Scenario::kOutdoor, Scenario::kRoom}) {
    const World world = World::generate(s, 4);
    const auto& route = world.route_W();
    int checked = 0;
    for (int k = 0; k < 200; ++k) {
      const Vec3 o = route[rng.integer(0, static_cast<int>(route.size()) - 1)];
      const Vec3 d = Vec3(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-0.5, 0.5)).normalized();
      const auto hit = world.raycast(o, d, 60.0);
      double travelled = 0;
      int steps = 0;
      for (double step = world.distance_to_surface(o); step > 1e-7 && travelled < 60.0 && steps < 5000; ++steps) {
        travelled += step;
        step = world.distance_to_surface(o + travelled * d);
      }
      if (steps == 5000) continue;  // grazing ray: sphere tracing did not converge
      ++checked;
      if (!hit) {
        EXPECT_GE(travelled, 60.0) << scenario_name(s);
        continue;
      }
      EXPECT_NEAR(travelled, hit->range_m, 1e-4) << scenario_name(s) << " from " << o.transpose() << " along " << d.transpose();
      EXPECT_LT(world.distance_to_surface(o + hit->range_m * d), 1e-6);
      EXPECT_LE(hit->normal_W.dot(d), 0.0) << "normal faces the ray origin";
      EXPECT_NEAR(hit->normal_W.norm(), 1.0, 1e-9);
    }
    EXPECT_GT(checked, 150) << scenario_name(s);
  }
}

TEST(Shapes, UvIsContinuousInMetresAcrossAFace) {
  const World world = World::generate(Scenario::kTunnel, 2);
  const Vec3 o = world.route_W().front();
  // Two nearby rays on the vault: their uv distance equals the distance between the hit points.
  for (const Vec3& d : {Vec3(0.3, 0.2, 0.9), Vec3(0.1, -0.9, 0.4), Vec3(0.2, 0.95, 0.1)}) {
    const Vec3 d0 = d.normalized(), d1 = (d + Vec3(0, 0.002, 0.001)).normalized();
    const auto h0 = world.raycast(o, d0, 50), h1 = world.raycast(o, d1, 50);
    ASSERT_TRUE(h0 && h1);
    const double metric = (o + h0->range_m * d0 - o - h1->range_m * d1).norm();
    EXPECT_NEAR((h0->uv_m - h1->uv_m).norm(), metric, 0.02 * metric);
  }
}

}  // namespace
}  // namespace vilslam::sim
