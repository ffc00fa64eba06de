// Highbay (an open warehouse with racks, pillars and clutter) and the huge loop (the highbay, out along
// a long narrow corridor and back in).
#include <cmath>

#include "sim/corridor.h"
#include "sim/enclosure.h"
#include "sim/rack.h"
#include "sim/world_builders.h"

namespace vilslam::sim {
namespace {

constexpr double kSensorHeight = 1.2;
constexpr double kRouteStep = 0.5;
constexpr double kTurnRadius = 1.5;
constexpr double kAisle = 2.0;     // half width of the aisle the route follows
constexpr double kWallGap = 3.6;   // from the route rectangle to the hall walls (x)
constexpr double kRackGap = 4.0;   // from the route rectangle to the hall walls (y), wall racks included
constexpr double kHallHeight = 9.0;

struct Palette {
  int floor, wall, ceiling, pillar, truss, stripe, lamp, sign;
  RackStyle rack;
  std::vector<int> clutter;
  CorridorStyle corridor;
};

Palette make_palette(SceneBuilder& builder) {
  using K = Material::Kind;
  Rng& rng = builder.rng();
  Palette p;
  p.floor = builder.material(K::kConcrete, 0.45f, 0.25f);
  p.wall = builder.material(K::kConcrete, 0.6f, 0.2f);
  p.ceiling = builder.material(K::kConcrete, 0.5f, 0.15f);
  p.pillar = builder.material(K::kConcrete, 0.55f, 0.3f);
  p.truss = builder.material(K::kPlain, 0.3f, 0.1f);
  p.stripe = builder.material(K::kPlain, 0.9f, 0.02f);
  p.lamp = builder.material(K::kPlain, 0.97f, 0.0f);
  p.sign = builder.material(K::kPoster, 0.5f, 0.7f);
  p.rack.upright = builder.material(K::kPlain, 0.25f, 0.1f);
  p.rack.deck = builder.material(K::kPlain, 0.6f, 0.15f);
  for (int k = 0; k < 6; ++k) {
    p.rack.goods.push_back(builder.material(K::kClutter, static_cast<float>(rng.uniform(0.3, 0.75)), 0.35f));
  }
  p.clutter = p.rack.goods;
  p.clutter.push_back(builder.material(K::kClutter, 0.35f, 0.3f));
  p.corridor.wall = builder.material(K::kPlain, 0.78f, 0.02f);
  p.corridor.floor = builder.material(K::kPlain, 0.45f, 0.06f);
  p.corridor.ceiling = builder.material(K::kPlain, 0.85f, 0.02f);
  p.corridor.door = builder.material(K::kPlain, 0.35f, 0.05f);
  p.corridor.poster = builder.material(K::kPoster, 0.5f, 0.6f);
  p.corridor.sign = p.sign;
  p.corridor.light = p.lamp;
  return p;
}

// The route rectangle [0, a] x [0, b] whose rounded perimeter is length_m (aspect 3:2).
Eigen::Vector2d hall_size(double length_m) {
  const double corner_loss = (8 - 2 * M_PI) * kTurnRadius;
  const double b = (length_m + corner_loss) / 5.0;
  return Eigen::Vector2d(1.5 * b, b);
}

// The hall around the route rectangle [0, a] x [0, b]: walls, floor, ceiling, trusses, racks in the
// middle block and along the long walls, pillars and clutter. The route must be set already.
void add_hall(SceneBuilder& builder, const Palette& p, double a, double b, const std::vector<Doorway>& doorways) {
  Rng& rng = builder.rng();
  const Eigen::AlignedBox3d hall(Vec3(-kWallGap, -kRackGap, 0), Vec3(a + kWallGap, b + kRackGap, kHallHeight));
  const Enclosure enclosure = add_enclosure(builder, hall, Walls{p.floor, p.ceiling, p.wall}, doorways);
  for (Quad* wall : enclosure.walls) {
    const double u = rng.uniform(1.0, 5.0);
    wall->decals.push_back({0, Eigen::AlignedBox2d(Eigen::Vector2d(u, 2.0), Eigen::Vector2d(u + 1.0, 2.7)), p.sign});
  }
  // Trusses under the roof every 6 m, lamps hanging from them.
  for (double x = 1.0; x < a + kWallGap; x += 6.0) {
    builder.add(Box::axis_aligned(Vec3(x, -kRackGap, 7.8), Vec3(x + 0.3, b + kRackGap, 8.4)), p.truss);
    for (double y = 2.0; y < b; y += 8.0) {
      builder.add(Box::axis_aligned(Vec3(x - 0.3, y, 7.2), Vec3(x + 0.6, y + 1.2, 7.35)), p.lamp);
    }
  }
  // Racks: back-to-back rows in the middle block, single rows along the long walls.
  RackStyle rack = p.rack;
  const double x0 = kAisle + 1.0, x1 = a - kAisle - 1.0;
  for (double y = kAisle + 0.5; y + 2 * rack.depth_m <= b - kAisle - 0.5; y += 2 * rack.depth_m + 3.0) {
    rack.height_m = rng.uniform(4.5, 6.0);
    add_rack(builder, rack, x0, x1, y + rack.depth_m, -1.0);
    add_rack(builder, rack, x0, x1, y + rack.depth_m, 1.0);
    add_floor_clutter(builder, Eigen::AlignedBox2d(Eigen::Vector2d(x0, y + 2 * rack.depth_m + 0.6),
                                                   Eigen::Vector2d(x1, y + 2 * rack.depth_m + 2.4)),
                      3, p.clutter, 1.0);
  }
  rack.height_m = 6.0;
  add_rack(builder, rack, -kAisle, a + kAisle, -kRackGap + 0.1, 1.0);
  add_rack(builder, rack, -kAisle, a + kAisle, b + kRackGap - 0.1, -1.0);
  // Pillars between the route and the wall racks and along the short walls (where clear of the route).
  for (double x = 0; x <= a; x += 8.0) {
    for (const double y : {-2.5, b + 2.5}) {
      builder.add(Box(Vec3(x, y, 0.5 * kHallHeight), Mat3::Identity(), Vec3(0.25, 0.25, 0.5 * kHallHeight)), p.pillar);
    }
  }
  for (double y = 4.0; y < b - 2.0; y += 8.0) {
    for (const double x : {-2.5, a + 2.5}) {
      const Box pillar(Vec3(x, y, 0.5 * kHallHeight), Mat3::Identity(), Vec3(0.25, 0.25, 0.5 * kHallHeight));
      if (route_clearance(builder.route(), pillar) >= 1.0) builder.add(pillar, p.pillar);
    }
  }
  for (const double x : {-kWallGap + 0.1, a + kWallGap - 0.1}) {
    const double lo = std::min(x, x < 0 ? -2.3 : a + 2.3), hi = std::max(x, x < 0 ? -2.3 : a + 2.3);
    add_floor_clutter(builder, Eigen::AlignedBox2d(Eigen::Vector2d(lo, -1.5), Eigen::Vector2d(hi, b + 1.5)), 8, p.clutter, 1.0);
  }
  // Floor paint along both edges of the aisle the route follows (floor uv = (x, y) - hall min).
  const Eigen::Vector2d origin(-kWallGap, -kRackGap);
  for (const double e : {-kAisle, kAisle}) {
    const Eigen::Vector2d lo = Eigen::Vector2d(e, e) - origin, hi = Eigen::Vector2d(a - e, b - e) - origin;
    auto stripe = [&](const Eigen::Vector2d& from, const Eigen::Vector2d& to) {
      enclosure.floor->decals.push_back(
          {0, Eigen::AlignedBox2d(from.cwiseMin(to) - Eigen::Vector2d(0.05, 0.05), from.cwiseMax(to) + Eigen::Vector2d(0.05, 0.05)),
           p.stripe});
    };
    stripe(lo, Eigen::Vector2d(hi.x(), lo.y()));
    stripe(Eigen::Vector2d(hi.x(), lo.y()), hi);
    stripe(hi, Eigen::Vector2d(lo.x(), hi.y()));
    stripe(Eigen::Vector2d(lo.x(), hi.y()), lo);
  }
}

}  // namespace

void build_highbay(SceneBuilder& builder, double length_m) {
  const Palette palette = make_palette(builder);
  const Eigen::Vector2d size = hall_size(length_m);
  const Polygon2 corners = {{0, 0}, {size.x(), 0}, {size.x(), size.y()}, {0, size.y()}};
  builder.set_route(rounded_loop(corners, kTurnRadius, kRouteStep, kSensorHeight));
  add_hall(builder, palette, size.x(), size.y(), {});
}

void build_loop(SceneBuilder& builder, double length_m) {
  const Palette palette = make_palette(builder);
  // The hall of the highbay preset; the corridor takes the rest of the length: it leaves through a door
  // in the east wall, runs east, turns north and comes back west through a second door.
  const Eigen::Vector2d size = hall_size(preset_length_m(Scenario::kHighbay));
  const double a = size.x(), b = size.y();
  const double y_out = 0.3 * b, y_in = 0.7 * b;
  const double x_wall = a + kWallGap;
  auto corners_for = [&](double x_far) {
    return Polygon2{{0, 0}, {a, 0}, {a, y_out}, {x_far, y_out}, {x_far, y_in}, {a, y_in}, {a, b}, {0, b}};
  };
  const double x_try = x_wall + 20.0;
  double x_far = x_try + 0.5 * (length_m - rounded_loop_length(corners_for(x_try), kTurnRadius));
  x_far = std::max(x_far, x_wall + 6.0);
  builder.set_route(rounded_loop(corners_for(x_far), kTurnRadius, kRouteStep, kSensorHeight));
  CorridorStyle style = palette.corridor;
  add_corridor(builder, Polygon2{{x_wall, y_out}, {x_far, y_out}, {x_far, y_in}, {x_wall, y_in}}, false, style);
  add_hall(builder, palette, a, b,
           {Doorway{1, y_out, style.width_m, style.height_m}, Doorway{1, y_in, style.width_m, style.height_m}});
}

}  // namespace vilslam::sim
