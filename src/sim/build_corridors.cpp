// Hallway (a loop of narrow corridors with plain walls) and tunnel (a long arched tube).
#include <cmath>

#include "sim/corridor.h"
#include "sim/world_builders.h"

namespace vilslam::sim {
namespace {

constexpr double kSensorHeight = 1.2;
constexpr double kRouteStep = 0.5;

}  // namespace

void build_hallway(SceneBuilder& builder, double length_m) {
  Rng& rng = builder.rng();
  using K = Material::Kind;
  CorridorStyle style;
  style.width_m = rng.uniform(2.0, 2.4);
  style.height_m = rng.uniform(2.8, 3.2);
  style.wall = builder.material(K::kPlain, 0.78f, 0.02f);
  style.floor = builder.material(K::kPlain, 0.45f, 0.06f);
  style.ceiling = builder.material(K::kPlain, 0.85f, 0.02f);
  style.door = builder.material(K::kPlain, 0.35f, 0.05f);
  style.poster = builder.material(K::kPoster, 0.5f, 0.6f);
  style.sign = builder.material(K::kPoster, 0.6f, 0.7f);
  style.light = builder.material(K::kPlain, 0.97f, 0.0f);
  // An office corridor: a door, poster or sign every ~3 m of each wall (the plain paint stays plain).
  style.decals_per_10m = 6.0;

  // A rectilinear loop with corner notches (several turns), scaled so the rounded route has length_m.
  const double radius = 1.5;
  const double aspect = rng.uniform(1.2, 1.8);
  // Notches need room: at least 3.5 m between parallel corridors and 3 m for each rounded corner.
  Polygon2 loop = rectilinear_loop(rng, aspect, 1.0, length_m >= 80 ? 2 : 0, 0.22);
  scale_to_length(&loop, radius, length_m);
  add_corridor(builder, loop, true, style);
  // The route starts and ends mid-way along the longest corridor (the walls keep the plain loop), so the
  // return approaches the start down that corridor, as in the paper's run, not at a corner facing a wall.
  builder.set_route(rounded_loop(start_mid_longest_edge(loop), radius, kRouteStep, kSensorHeight));
}

void build_tunnel(SceneBuilder& builder, double length_m) {
  Rng& rng = builder.rng();
  using K = Material::Kind;
  const int vault = builder.material(K::kConcrete, 0.55f, 0.12f);
  const int floor = builder.material(K::kConcrete, 0.35f, 0.15f);
  const int lamp = builder.material(K::kPlain, 0.97f, 0.0f);
  const int sign = builder.material(K::kPoster, 0.6f, 0.7f);

  // Out along one lane and back along the other, turning on semicircles: the route length is
  // 2 (straight + lane gap) - 4 (2 r - r pi / 2) with r = half the lane gap.
  const double axis_height = 1.0;
  const double tube_radius = 3.0;
  const double lane = 1.25;
  const double straight = 0.5 * (length_m - 2 * M_PI * lane) + 2 * lane;
  const Polygon2 corners = {{0, -lane}, {straight, -lane}, {straight, lane}, {0, lane}};
  builder.set_route(rounded_loop(corners, lane, kRouteStep, kSensorHeight));

  // The tube runs past both turnarounds by more than a VLP-16's range, so no end is ever seen.
  const double margin = 130.0;
  ArchedTube& tube = builder.add(ArchedTube(Vec3(-margin, 0, axis_height), 0.0, straight + 2 * margin, tube_radius, axis_height), vault);
  tube.face_material[1] = floor;
  const double arc = (M_PI + 2 * std::asin(axis_height / tube_radius)) * tube_radius;
  for (double s = rng.uniform(0, 10); s < straight + 2 * margin; s += 12.0) {
    tube.decals.push_back({0, Eigen::AlignedBox2d(Eigen::Vector2d(s, 0.5 * arc - 0.15), Eigen::Vector2d(s + 1.5, 0.5 * arc + 0.15)), lamp});
  }
  for (double s = rng.uniform(0, 20); s < straight + 2 * margin; s += rng.uniform(20, 40)) {
    const double v = rng.chance(0.5) ? 2.2 : arc - 2.8;
    tube.decals.push_back({0, Eigen::AlignedBox2d(Eigen::Vector2d(s, v), Eigen::Vector2d(s + 0.8, v + 0.5)), sign});
  }
}

}  // namespace vilslam::sim
