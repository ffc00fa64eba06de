// The room: a textured box the size of the EuRoC Vicon room (V1 sequences fly inside it) with clutter
// on the walls and the floor, and a route looping inside. A recorded flight that leaves that box (the
// Machine Hall sequences span 13 x 10 m) gets a room grown around it, dressed at the same density.
#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

#include "sim/enclosure.h"
#include "sim/route.h"
#include "sim/world_builders.h"

namespace vilslam::sim {
namespace {

// The EuRoC V1 ground truth spans x [-2.3, 2.2], y [-2.5, 3.5], z [0.8, 2.6]; V2 reaches x -3.8.
const Eigen::AlignedBox3d kRoom(Vec3(-4.5, -3.6, 0.0), Vec3(3.7, 4.6, 4.0));
const Eigen::Vector2d kRouteCenter(0.0, 0.5);
constexpr double kWallMarginM = 1.5;     // a grown room's walls stand this far from the flight
constexpr double kFloorMarginM = 0.7;    // its floor this far below the lowest position (above the floor mats)
constexpr double kCeilingMarginM = 2.0;  // its ceiling this far above the highest

// Where the clutter goes: the Vicon room's hand-placed layout, or the same scaled to a grown room.
struct RoomLayout {
  Eigen::AlignedBox3d box = kRoom;
  Eigen::AlignedBox2d floor_clutter{Eigen::Vector2d(-2.5, -2.5), Eigen::Vector2d(2.0, 3.5)};
  std::vector<double> beam_y{-0.8, 2.2};
  double beam_z0 = 3.6, beam_z1 = 3.85;
  double density = 1.0;  // clutter counts scale with this (floor area or wall length over the Vicon room's)
};

RoomLayout room_layout(const std::optional<Eigen::AlignedBox3d>& flight_W) {
  RoomLayout layout;
  if (!flight_W || kRoom.contains(*flight_W)) return layout;
  const Vec3 margin(kWallMarginM, kWallMarginM, 0.0);
  Eigen::AlignedBox3d box(flight_W->min() - margin, flight_W->max() + margin);
  box.min().z() = flight_W->min().z() - kFloorMarginM;
  box.max().z() = std::max(box.min().z() + kRoom.sizes().z(), flight_W->max().z() + kCeilingMarginM);
  box.extend(Eigen::AlignedBox3d(Vec3(kRoom.min().x(), kRoom.min().y(), box.min().z()),
                                 Vec3(kRoom.max().x(), kRoom.max().y(), box.max().z())));
  layout.box = box;
  const Eigen::Vector2d lo = box.min().head<2>(), hi = box.max().head<2>();
  layout.floor_clutter = Eigen::AlignedBox2d(lo + Eigen::Vector2d(2.0, 1.1), hi - Eigen::Vector2d(1.7, 1.1));
  layout.beam_y.clear();
  for (double y = lo.y() + 2.8; y < hi.y() - 1.0; y += 3.0) layout.beam_y.push_back(y);
  layout.beam_z1 = box.max().z() - 0.15;
  layout.beam_z0 = layout.beam_z1 - 0.25;
  layout.density = box.sizes().head<2>().prod() / kRoom.sizes().head<2>().prod();
  return layout;
}

int scaled(int count, double factor) { return std::max(count, static_cast<int>(std::lround(count * factor))); }

// An ellipse at a height that rises and falls twice per lap, sampled every ~step_m; first == last.
std::vector<Vec3> elliptic_loop(double rx, double ry, double step_m) {
  const int n = std::max(16, static_cast<int>(std::ceil(M_PI * (rx + ry) / step_m)));
  std::vector<Vec3> route;
  for (int k = 0; k < n; ++k) {
    const double a = 2 * M_PI * k / n;
    route.emplace_back(kRouteCenter.x() + rx * std::cos(a), kRouteCenter.y() + ry * std::sin(a), 1.3 + 0.3 * std::sin(2 * a));
  }
  route.push_back(route.front());
  return route;
}

// Random posters and wall-mounted boxes on one wall quad running along `dir` from `start`.
void dress_wall(SceneBuilder& builder, Quad& wall, const Vec3& start, const Vec3& dir, double length, int poster,
                int clutter, bool boxes) {
  Rng& rng = builder.rng();
  // Ten posters and six boxes per wall of the Vicon room (8.2 m), as dense on longer walls.
  const double per_room_wall = length / kRoom.sizes().x();
  for (int k = 0; k < scaled(10, per_room_wall); ++k) {
    const double w = rng.uniform(0.4, 1.2), h = rng.uniform(0.4, 1.0);
    const double u = rng.uniform(0.2, length - 0.2 - w), v = rng.uniform(0.3, 3.6 - h);
    wall.decals.push_back({0, Eigen::AlignedBox2d(Eigen::Vector2d(u, v), Eigen::Vector2d(u + w, v + h)), poster});
  }
  if (!boxes) return;
  const Vec3 inward = Vec3::UnitZ().cross(dir);
  for (int k = 0; k < scaled(6, per_room_wall); ++k) {
    const double w = rng.uniform(0.3, 0.8), h = rng.uniform(0.2, 0.6), depth = rng.uniform(0.15, 0.3);
    const double u = rng.uniform(0.3, length - 0.3 - w), z = rng.uniform(0.2, 3.5 - h);
    const Vec3 center = start + (u + 0.5 * w) * dir + 0.5 * depth * inward + Vec3(0, 0, z + 0.5 * h);
    Mat3 R;
    R << dir, inward, Vec3::UnitZ();
    builder.add(Box(center, R, Vec3(0.5 * w, 0.5 * depth, 0.5 * h)), clutter);
  }
}

}  // namespace

void build_room(SceneBuilder& builder, double length_m, const std::optional<Eigen::AlignedBox3d>& flight_W) {
  Rng& rng = builder.rng();
  using K = Material::Kind;
  const int floor = builder.material(K::kConcrete, 0.4f, 0.3f);
  const int wall = builder.material(K::kConcrete, 0.6f, 0.25f);
  const int ceiling = builder.material(K::kConcrete, 0.7f, 0.15f);
  const int poster = builder.material(K::kPoster, 0.5f, 0.7f);
  std::vector<int> clutter;
  for (int k = 0; k < 4; ++k) clutter.push_back(builder.material(K::kClutter, rng.uniform(0.3f, 0.7f), 0.4f));

  // One lap of length_m: the ellipse is scaled until its length (height changes included) matches.
  double scale = 1.0;
  for (int k = 0; k < 4; ++k) {
    scale = std::min(scale * length_m / polyline_length(elliptic_loop(1.8 * scale, 2.4 * scale, 0.25)), 1.25);
  }
  builder.set_route(elliptic_loop(1.8 * scale, 2.4 * scale, 0.25));

  const RoomLayout layout = room_layout(flight_W);
  const Eigen::AlignedBox3d& room = layout.box;
  const Enclosure walls = add_enclosure(builder, room, Walls{floor, ceiling, wall});
  const Vec3 lo = room.min(), hi = room.max();
  const Vec3 starts[4] = {lo, Vec3(hi.x(), lo.y(), lo.z()), Vec3(hi.x(), hi.y(), lo.z()), Vec3(lo.x(), hi.y(), lo.z())};
  const Vec3 dirs[4] = {Vec3::UnitX(), Vec3::UnitY(), -Vec3::UnitX(), -Vec3::UnitY()};
  for (int k = 0; k < 4; ++k) {
    const double length = (k % 2 == 0) ? room.sizes().x() : room.sizes().y();
    dress_wall(builder, *walls.walls[k], starts[k], dirs[k], length, poster, rng.pick(clutter), k != 3);
  }
  // Floor clutter: low mats and boxes in the middle, taller boxes and stands along the walls.
  const Eigen::AlignedBox2d& mats = layout.floor_clutter;
  for (int k = 0; k < scaled(6, layout.density); ++k) {
    const Vec3 c(rng.uniform(mats.min().x(), mats.max().x()), rng.uniform(mats.min().y(), mats.max().y()), lo.z());
    const double w = rng.uniform(0.5, 1.5), d = rng.uniform(0.5, 1.5), h = rng.uniform(0.05, 0.35);
    builder.add(Box(c + Vec3(0, 0, 0.5 * h), Eigen::AngleAxisd(rng.uniform(0, M_PI), Vec3::UnitZ()).toRotationMatrix(),
                    Vec3(0.5 * w, 0.5 * d, 0.5 * h)),
                rng.pick(clutter));
  }
  for (int k = 0; k < scaled(10, std::sqrt(layout.density)); ++k) {
    const double w = rng.uniform(0.3, 0.7), h = rng.uniform(0.3, 1.5);
    const int side = rng.integer(0, 2);  // not along the x = min wall, where V2 flies close
    const double along = rng.uniform(0.6, (side % 2 == 0 ? room.sizes().x() : room.sizes().y()) - 0.6);
    const Vec3 inward = Vec3::UnitZ().cross(dirs[side]);
    const Vec3 c = starts[side] + along * dirs[side] + (0.5 * w + 0.05) * inward + Vec3(0, 0, 0.5 * h);
    builder.add(Box(c, Mat3::Identity(), Vec3(0.5 * w, 0.5 * w, 0.5 * h)), rng.pick(clutter));
  }
  for (const Eigen::Vector2d& corner : {Eigen::Vector2d(hi.x() - 0.5, lo.y() + 0.5),
                                        Eigen::Vector2d(hi.x() - 0.5, hi.y() - 0.5),
                                        Eigen::Vector2d(lo.x() + 0.5, hi.y() - 0.5)}) {
    builder.add(Cylinder(corner, lo.z(), lo.z() + rng.uniform(1.2, 2.5), rng.uniform(0.15, 0.3)), rng.pick(clutter));
  }
  // Ceiling beams across the room (two in the Vicon room, one per 3 m in a grown one).
  for (const double y : layout.beam_y) {
    builder.add(Box::axis_aligned(Vec3(lo.x(), y - 0.15, layout.beam_z0), Vec3(hi.x(), y + 0.15, layout.beam_z1)),
                rng.pick(clutter));
  }
}

}  // namespace vilslam::sim
