#include "sim/corridor.h"

#include <cmath>

namespace vilslam::sim {
namespace {

Eigen::Vector2d left_normal(const Eigen::Vector2d& d) { return Eigen::Vector2d(-d.y(), d.x()); }

// The wall line at signed lateral offset through vertex i: the miter of the two offset edges, or the
// plain perpendicular offset at an open end.
Eigen::Vector2d offset_vertex(const Polygon2& line, bool closed, int i, double offset) {
  const int n = static_cast<int>(line.size());
  const bool has_prev = closed || i > 0, has_next = closed || i < n - 1;
  const Eigen::Vector2d d_in = has_prev ? (line[i] - line[(i + n - 1) % n]).normalized() : Eigen::Vector2d::Zero();
  const Eigen::Vector2d d_out = has_next ? (line[(i + 1) % n] - line[i]).normalized() : Eigen::Vector2d::Zero();
  if (!has_prev) return line[i] + offset * left_normal(d_out);
  if (!has_next) return line[i] + offset * left_normal(d_in);
  const Eigen::Vector2d miter = (left_normal(d_in) + left_normal(d_out)).normalized();
  return line[i] + offset / miter.dot(left_normal(d_in)) * miter;
}

void add_wall_decals(SceneBuilder& builder, Quad& wall, double length, const CorridorStyle& style) {
  Rng& rng = builder.rng();
  const int count = static_cast<int>(std::floor(length / 10.0 * style.decals_per_10m * 0.5 + rng.uniform()));
  for (int k = 0; k < count; ++k) {
    const double kind = rng.uniform();
    double w, h, z;
    int material;
    if (kind < 0.4) {
      w = 0.9, h = 2.1, z = 0.0, material = style.door;
    } else if (kind < 0.85) {
      w = rng.uniform(0.5, 1.0), h = rng.uniform(0.6, 1.0), z = rng.uniform(1.1, 1.5), material = style.poster;
    } else {
      w = rng.uniform(0.3, 0.6), h = 0.2, z = 2.3, material = style.sign;
    }
    if (length < w + 1.0) continue;
    const double u = rng.uniform(0.5, length - 0.5 - w);
    wall.decals.push_back({0, Eigen::AlignedBox2d(Eigen::Vector2d(u, z), Eigen::Vector2d(u + w, z + h)), material});
  }
}

}  // namespace

void add_corridor(SceneBuilder& builder, const Polygon2& centerline, bool closed, const CorridorStyle& style) {
  const int n = static_cast<int>(centerline.size());
  const int segments = closed ? n : n - 1;
  const double half = 0.5 * style.width_m;
  const Vec3 up = Vec3::UnitZ();
  for (int i = 0; i < segments; ++i) {
    const int j = (i + 1) % n;
    for (const double side : {-half, half}) {
      const Eigen::Vector2d a = offset_vertex(centerline, closed, i, side);
      const Eigen::Vector2d b = offset_vertex(centerline, closed, j, side);
      const Eigen::Vector2d ab = b - a;
      const double length = ab.norm();
      Quad& wall = builder.add(Quad(Vec3(a.x(), a.y(), 0), Vec3(ab.x(), ab.y(), 0), length, up, style.height_m),
                               style.wall);
      add_wall_decals(builder, wall, length, style);
    }
    // Floor and ceiling of the segment: from half a width before its start to half a width before its
    // end, so that each corner square is covered once (an open end stops at the end point).
    const Eigen::Vector2d d = (centerline[j] - centerline[i]).normalized();
    const double length = (centerline[j] - centerline[i]).norm();
    const double from = (closed || i > 0) ? -half : 0.0;
    const double to = (closed || i < segments - 1) ? length - half : length;
    const Eigen::Vector2d corner = centerline[i] + from * d - half * left_normal(d);
    const Vec3 u(d.x(), d.y(), 0), v(-d.y(), d.x(), 0);
    builder.add(Quad(Vec3(corner.x(), corner.y(), 0), u, to - from, v, style.width_m, true), style.floor);
    Quad& ceiling = builder.add(Quad(Vec3(corner.x(), corner.y(), style.height_m), u, to - from, v, style.width_m),
                                style.ceiling);
    for (double s = 2.5; s + 1.2 < to - from; s += 5.0) {
      ceiling.decals.push_back({0, Eigen::AlignedBox2d(Eigen::Vector2d(s, half - 0.3), Eigen::Vector2d(s + 1.2, half + 0.3)),
                                style.light});
    }
  }
}

}  // namespace vilslam::sim
