// Outdoor: streets around city blocks on ground with a gentle slope, buildings, streetlights, poles,
// trees and parked cars.
#include <algorithm>
#include <cmath>

#include "sim/route.h"
#include "sim/world_builders.h"

namespace vilslam::sim {
namespace {

constexpr double kSensorHeight = 1.5;
constexpr double kRouteStep = 0.5;
constexpr double kTurnRadius = 8.0;
constexpr double kMargin = 40.0;  // ground beyond the route (past the buildings)

struct Palette {
  int ground, road, marking, pole, lamp, trunk, car;
  std::vector<int> facades, foliage;
};

Palette make_palette(SceneBuilder& builder) {
  using K = Material::Kind;
  Rng& rng = builder.rng();
  Palette p;
  p.ground = builder.material(K::kGround, 0.45f, 0.3f);
  p.road = builder.material(K::kGround, 0.25f, 0.15f);
  p.marking = builder.material(K::kPlain, 0.9f, 0.02f);
  p.pole = builder.material(K::kPlain, 0.35f, 0.1f);
  p.lamp = builder.material(K::kPlain, 0.9f, 0.05f);
  p.trunk = builder.material(K::kConcrete, 0.3f, 0.3f);
  p.car = builder.material(K::kClutter, 0.4f, 0.4f);
  for (int k = 0; k < 6; ++k) p.facades.push_back(builder.material(K::kConcrete, rng.uniform(0.35f, 0.75f), 0.35f));
  for (int k = 0; k < 3; ++k) p.foliage.push_back(builder.material(K::kFoliage, rng.uniform(0.2f, 0.4f), 0.5f));
  return p;
}

// Adds the shape when it keeps clear_m from the route; returns whether it did.
template <typename ShapeT>
bool add_clear(SceneBuilder& builder, ShapeT shape, int material, double clear_m) {
  if (route_clearance(builder.route(), shape) < clear_m) return false;
  builder.add(std::move(shape), material);
  return true;
}

}  // namespace

void build_outdoor(SceneBuilder& builder, double length_m) {
  Rng& rng = builder.rng();
  const Palette p = make_palette(builder);
  // Streets: a rectilinear loop around blocks, scaled to the length, on the plane z = slope * x.
  const double aspect = rng.uniform(1.2, 1.6);
  Polygon2 loop = rectilinear_loop(rng, aspect, 1.0, length_m >= 400 ? 1 : 0, 0.3);  // notch >= 2 turn radii
  scale_to_length(&loop, kTurnRadius, length_m);
  const double slope = rng.uniform(0.02, 0.04);
  auto ground_z = [&](double x) { return slope * x; };
  std::vector<Vec3> route = rounded_loop(loop, kTurnRadius, kRouteStep, 0.0);
  for (Vec3& q : route) q.z() = ground_z(q.x()) + kSensorHeight;
  builder.set_route(route);

  Eigen::AlignedBox2d streets;
  for (const auto& c : loop) streets.extend(c);
  const Eigen::Vector2d lo = streets.min().array() - kMargin, hi = streets.max().array() + kMargin;
  const double stretch = std::sqrt(1 + slope * slope);  // ground uv u runs along the slope
  const Vec3 along_x = Vec3(1, 0, slope).normalized();
  Quad& ground = builder.add(Quad(Vec3(lo.x(), lo.y(), ground_z(lo.x())), along_x, (hi.x() - lo.x()) * stretch,
                                  Vec3::UnitY(), hi.y() - lo.y(), true),
                             p.ground);
  auto ground_uv = [&](const Eigen::Vector2d& xy) { return Eigen::Vector2d((xy.x() - lo.x()) * stretch, xy.y() - lo.y()); };
  const std::size_t n = loop.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector2d a = loop[i], b = loop[(i + 1) % n];
    const Eigen::Vector2d road_lo = a.cwiseMin(b) - Eigen::Vector2d(4, 4), road_hi = a.cwiseMax(b) + Eigen::Vector2d(4, 4);
    ground.decals.push_back({0, Eigen::AlignedBox2d(ground_uv(road_lo), ground_uv(road_hi)), p.road});
  }
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector2d a = loop[i], b = loop[(i + 1) % n];
    const Eigen::Vector2d d = (b - a).normalized();
    const double len = (b - a).norm();
    for (double s = 10.0; s + 3.0 < len - 10.0; s += 6.0) {  // dashed centre line
      const Eigen::Vector2d m0 = a + s * d, m1 = a + (s + 3.0) * d;
      const Eigen::Vector2d half(0.08, 0.08);
      ground.decals.push_back({0, Eigen::AlignedBox2d(ground_uv(m0.cwiseMin(m1) - half), ground_uv(m0.cwiseMax(m1) + half)), p.marking});
    }
  }

  // Along every street, on both sides: buildings set back, then streetlights, poles, trees and cars.
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector2d a = loop[i], b = loop[(i + 1) % n];
    const Eigen::Vector2d d = (b - a).normalized();
    const double len = (b - a).norm();
    const double yaw = std::atan2(d.y(), d.x());
    const Mat3 R = Eigen::AngleAxisd(yaw, Vec3::UnitZ()).toRotationMatrix();
    for (const double side : {-1.0, 1.0}) {
      const Eigen::Vector2d out = side * Eigen::Vector2d(-d.y(), d.x());
      for (double s = rng.uniform(0, 6); s < len;) {
        const double width = rng.uniform(8, 25), depth = rng.uniform(8, 16), height = rng.uniform(4, 18);
        const double setback = rng.uniform(8, 12);
        const Eigen::Vector2d c = a + (s + 0.5 * width) * d + (setback + 0.5 * depth) * out;
        const double base = ground_z(c.x()) - 0.5 * std::abs(slope) * (width + depth) - 0.2;
        const double top = ground_z(c.x()) + height;
        add_clear(builder, Box(Vec3(c.x(), c.y(), 0.5 * (base + top)), R, Vec3(0.5 * width, 0.5 * depth, 0.5 * (top - base))),
                  rng.pick(p.facades), 6.0);
        s += width + rng.uniform(2, 8);
      }
      for (double s = rng.uniform(5, 20); s < len; s += rng.uniform(8, 14)) {
        const Eigen::Vector2d c = a + s * d + rng.uniform(4.5, 6.0) * out;
        const double z0 = ground_z(c.x());
        const double kind = rng.uniform();
        if (kind < 0.25) {  // streetlight: pole, arm over the street, lamp
          if (!add_clear(builder, Cylinder(c, z0 - 0.2, z0 + 6.0, 0.1), p.pole, 1.5)) continue;
          const Eigen::Vector2d arm = c - 0.8 * out;
          builder.add(Box(Vec3(arm.x(), arm.y(), z0 + 5.9), R, Vec3(0.05, 0.8, 0.05)), p.pole);
          const Eigen::Vector2d lamp = c - 1.5 * out;
          builder.add(Box(Vec3(lamp.x(), lamp.y(), z0 + 5.8), R, Vec3(0.3, 0.15, 0.08)), p.lamp);
        } else if (kind < 0.45) {  // sign post or bollard
          add_clear(builder, Cylinder(c, z0 - 0.2, z0 + rng.uniform(1.0, 2.8), rng.uniform(0.04, 0.08)), p.pole, 1.5);
        } else if (kind < 0.8) {  // tree: trunk and two crown tiers
          const double trunk_top = z0 + rng.uniform(2.4, 3.2), crown = rng.uniform(1.4, 2.2);
          if (!add_clear(builder, Cylinder(c, z0 - 0.2, trunk_top, rng.uniform(0.12, 0.22)), p.trunk, 1.5)) continue;
          const int leaves = rng.pick(p.foliage);
          add_clear(builder, Cylinder(c, trunk_top - 0.3, trunk_top + 2.0, crown), leaves, 1.0);
          add_clear(builder, Cylinder(c, trunk_top + 2.0, trunk_top + 3.2, 0.6 * crown), leaves, 1.0);
        } else {  // parked car
          const Eigen::Vector2d car = a + s * d + 3.4 * out;
          const double zc = ground_z(car.x());
          add_clear(builder, Box(Vec3(car.x(), car.y(), zc + 0.55), R, Vec3(2.1, 0.9, 0.55)), p.car, 1.5);
          add_clear(builder, Box(Vec3(car.x(), car.y(), zc + 1.3), R, Vec3(1.1, 0.8, 0.25)), p.car, 1.5);
        }
      }
    }
  }
}

}  // namespace vilslam::sim
