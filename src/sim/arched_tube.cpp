#include <algorithm>
#include <cmath>

#include "sim/shapes.h"
#include "sim/surface_grid.h"

namespace vilslam::sim {
namespace {

// Cross-section coordinates (y, z) relative to the tunnel axis: a circle of radius r cut by the floor
// line z = -h. Distance from q to the arc (the circle where z >= -h).
double distance_to_arc(const Eigen::Vector2d& q, double r, double h) {
  const double rho = q.norm();
  if (rho > 1e-12 && q.y() / rho * r >= -h) return std::abs(rho - r);  // radial projection lies on the arc
  const double w = std::sqrt(r * r - h * h);
  return std::min((q - Eigen::Vector2d(-w, -h)).norm(), (q - Eigen::Vector2d(w, -h)).norm());
}

// Distance from q to the floor chord from (-w, -h) to (w, -h).
double distance_to_chord(const Eigen::Vector2d& q, double w, double h) {
  const double dy = std::max(std::abs(q.x()) - w, 0.0);
  return std::hypot(dy, q.y() + h);
}

bool inside_section(const Eigen::Vector2d& q, double r, double h) { return q.squaredNorm() <= r * r && q.y() >= -h; }

}  // namespace

ArchedTube::ArchedTube(const Vec3& start_W, double yaw, double length, double radius, double axis_height)
    : start_(start_W),
      R_W_T_(Eigen::AngleAxisd(yaw, Vec3::UnitZ()).toRotationMatrix()),
      length_(length),
      radius_(radius),
      axis_height_(axis_height) {
  face_material.assign(4, 0);
}

double ArchedTube::floor_half_width() const { return std::sqrt(radius_ * radius_ - axis_height_ * axis_height_); }

Vec3 ArchedTube::to_local(const Vec3& p_W) const { return R_W_T_.transpose() * (p_W - start_); }

bool ArchedTube::intersect(const Ray& ray, double t_max, ShapeHit* hit) const {
  const Vec3 o = to_local(ray.origin);
  const Vec3 d = R_W_T_.transpose() * ray.dir;
  const double r = radius_, h = axis_height_, w = floor_half_width();
  double best = t_max;
  bool found = false;
  Vec3 n_local;
  auto accept = [&](double t, int face, const Vec3& normal, const Eigen::Vector2d& uv) {
    best = t, found = true;
    hit->face = face;
    n_local = normal;
    hit->uv = uv;
  };
  // Vault: (o_y + t d_y)^2 + (o_z + t d_z)^2 = r^2.
  const double a = d.y() * d.y() + d.z() * d.z();
  if (a > 1e-18) {
    const double b = o.y() * d.y() + o.z() * d.z();
    const double disc = b * b - a * (o.y() * o.y() + o.z() * o.z() - r * r);
    if (disc >= 0) {
      const double sq = std::sqrt(disc);
      for (const double t : {(-b - sq) / a, (-b + sq) / a}) {
        if (t <= kMinHitT || t > best) continue;
        const Vec3 q = o + t * d;
        if (q.z() < -h - kEdgeTol || q.x() < -kEdgeTol || q.x() > length_ + kEdgeTol) continue;
        // Angle from the -y direction, 0 at the floor edge y = -w, continuous over the whole arc.
        double angle = std::atan2(q.z(), -q.y()) + std::asin(h / r);
        if (angle < -1e-12) angle += 2 * M_PI;
        accept(t, 0, Vec3(0, -q.y() / r, -q.z() / r), Eigen::Vector2d(q.x(), angle * r));
        break;
      }
    }
  }
  if (std::abs(d.z()) > 1e-15) {
    const double t = (-h - o.z()) / d.z();
    const Vec3 q = o + t * d;
    if (t > kMinHitT && t <= best && std::abs(q.y()) <= w + kEdgeTol && q.x() >= -kEdgeTol && q.x() <= length_ + kEdgeTol) {
      accept(t, 1, Vec3(0, 0, 1), Eigen::Vector2d(q.x(), q.y() + w));
    }
  }
  if (std::abs(d.x()) > 1e-15) {
    for (const int face : {2, 3}) {
      const double s_cap = face == 2 ? 0.0 : length_;
      const double t = (s_cap - o.x()) / d.x();
      const Vec3 q = o + t * d;
      if (t <= kMinHitT || t > best || !inside_section(q.tail<2>(), r + kEdgeTol, h + kEdgeTol)) continue;
      accept(t, face, Vec3(face == 2 ? 1.0 : -1.0, 0, 0), Eigen::Vector2d(q.y() + w, q.z() + h));
    }
  }
  if (!found) return false;
  hit->t = best;
  hit->normal = R_W_T_ * n_local;  // pointing into the tunnel
  return true;
}

double ArchedTube::distance(const Vec3& p_W) const {
  // The surface is a union of products (interval along the axis) x (2D curve or region): distances add
  // in quadrature between the axial and the cross-section parts.
  const Vec3 q = to_local(p_W);
  const Eigen::Vector2d c = q.tail<2>();
  const double r = radius_, h = axis_height_;
  const double ds = std::max({-q.x(), q.x() - length_, 0.0});
  const double vault = std::hypot(ds, distance_to_arc(c, r, h));
  const double floor = std::hypot(ds, distance_to_chord(c, floor_half_width(), h));
  const double section = inside_section(c, r, h) ? 0.0
                                                 : std::min(distance_to_arc(c, r, h),
                                                            distance_to_chord(c, floor_half_width(), h));
  const double caps = std::hypot(std::min(std::abs(q.x()), std::abs(q.x() - length_)), section);
  return std::min({vault, floor, caps});
}

Eigen::AlignedBox3d ArchedTube::bounds() const {
  Eigen::AlignedBox3d box;
  for (const double s : {0.0, length_}) {
    for (const double y : {-radius_, radius_}) {
      for (const double z : {-axis_height_, radius_}) box.extend(start_ + R_W_T_ * Vec3(s, y, z));
    }
  }
  return box;
}

void ArchedTube::sample(double spacing_m, std::vector<SurfacePoint>* out) const {
  const double r = radius_, h = axis_height_, w = floor_half_width();
  const double arc_angle = M_PI + 2 * std::asin(h / r);
  const double start_angle = M_PI + std::asin(h / r);  // angle (from +y towards +z) of the floor edge y = -w
  auto to_world = [&](double s, double y, double z) -> Vec3 { return start_ + R_W_T_ * Vec3(s, y, z); };
  for_each_grid_point(length_, arc_angle * r, spacing_m, [&](double s, double v) {
    const double angle = start_angle - v / r;
    out->push_back({to_world(s, r * std::cos(angle), r * std::sin(angle)), 0});
  });
  for_each_grid_point(length_, 2 * w, spacing_m, [&](double s, double v) { out->push_back({to_world(s, v - w, -h), 1}); });
  for_each_grid_point(2 * r, r + h, spacing_m, [&](double y, double z) {
    if (!inside_section(Eigen::Vector2d(y - r, z - h), r, h)) return;
    out->push_back({to_world(0, y - r, z - h), 2});
    out->push_back({to_world(length_, y - r, z - h), 3});
  });
}

}  // namespace vilslam::sim
