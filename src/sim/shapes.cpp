#include "sim/shapes.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "sim/surface_grid.h"

namespace vilslam::sim {
namespace {

constexpr double kContainTol = 1e-6;

// The two in-face axes of a box face whose normal is along `axis` (vertical faces: v is z).
void face_axes(int axis, int* u_axis, int* v_axis) {
  *u_axis = axis == 0 ? 1 : 0;
  *v_axis = axis == 2 ? 1 : 2;
}

}  // namespace

int Shape::material_at(int face, const Eigen::Vector2d& uv) const {
  for (auto it = decals.rbegin(); it != decals.rend(); ++it) {
    if (it->face == face && it->uv_box.contains(uv)) return it->material;
  }
  return face_material[face];
}

// ---------------------------------------------------------------- Box

Box::Box(const Vec3& center_W, const Mat3& R_W_B, const Vec3& half)
    : center_(center_W), R_W_B_(R_W_B), half_(half), aligned_(R_W_B.isIdentity(0.0)) {
  face_material.assign(6, 0);
}

Box Box::axis_aligned(const Vec3& min_W, const Vec3& max_W) {
  return Box(0.5 * (min_W + max_W), Mat3::Identity(), 0.5 * (max_W - min_W));
}

bool Box::intersect(const Ray& ray, double t_max, ShapeHit* hit) const {
  // Slab test in the box frame (Kay & Kajiya 1986).
  const Vec3 o = aligned_ ? Vec3(ray.origin - center_) : Vec3(R_W_B_.transpose() * (ray.origin - center_));
  const Vec3 d = aligned_ ? ray.dir : Vec3(R_W_B_.transpose() * ray.dir);
  double t_in = -std::numeric_limits<double>::infinity(), t_out = std::numeric_limits<double>::infinity();
  int axis_in = -1, axis_out = -1;
  for (int a = 0; a < 3; ++a) {
    if (std::abs(d[a]) < 1e-15) {
      if (std::abs(o[a]) > half_[a]) return false;
      continue;
    }
    const double inv = 1.0 / d[a];
    double t0 = (-half_[a] - o[a]) * inv, t1 = (half_[a] - o[a]) * inv;
    if (t0 > t1) std::swap(t0, t1);
    if (t0 > t_in) t_in = t0, axis_in = a;
    if (t1 < t_out) t_out = t1, axis_out = a;
    if (t_in > t_out) return false;
  }
  double t;
  int axis;
  if (t_in > kMinHitT) {
    t = t_in, axis = axis_in;
  } else if (t_out > kMinHitT) {
    t = t_out, axis = axis_out;
  } else {
    return false;
  }
  if (t > t_max) return false;
  const Vec3 q = o + t * d;
  const bool positive = q[axis] > 0;
  int u_axis, v_axis;
  face_axes(axis, &u_axis, &v_axis);
  hit->t = t;
  hit->face = 2 * axis + (positive ? 1 : 0);
  hit->normal = positive ? Vec3(R_W_B_.col(axis)) : Vec3(-R_W_B_.col(axis));
  hit->uv = Eigen::Vector2d(q[u_axis] + half_[u_axis], q[v_axis] + half_[v_axis]);
  return true;
}

double Box::distance(const Vec3& p) const {
  // Exact box SDF (Quilez): outside length(max(q,0)), inside max component of q.
  const Vec3 q = (R_W_B_.transpose() * (p - center_)).cwiseAbs() - half_;
  const double outside = q.cwiseMax(0.0).norm();
  const double inside = std::min(q.maxCoeff(), 0.0);
  return std::abs(outside + inside);
}

bool Box::contains(const Vec3& p) const {
  const Vec3 q = (R_W_B_.transpose() * (p - center_)).cwiseAbs() - half_;
  return q.maxCoeff() <= kContainTol;
}

Eigen::AlignedBox3d Box::bounds() const {
  const Vec3 extent = R_W_B_.cwiseAbs() * half_;
  return Eigen::AlignedBox3d(center_ - extent, center_ + extent);
}

void Box::sample(double spacing_m, std::vector<SurfacePoint>* out) const {
  for (int face = 0; face < 6; ++face) {
    const int axis = face / 2;
    const double side = (face % 2) ? 1.0 : -1.0;
    int u_axis, v_axis;
    face_axes(axis, &u_axis, &v_axis);
    for_each_grid_point(2 * half_[u_axis], 2 * half_[v_axis], spacing_m, [&](double u, double v) {
      Vec3 q;
      q[axis] = side * half_[axis];
      q[u_axis] = u - half_[u_axis];
      q[v_axis] = v - half_[v_axis];
      out->push_back({center_ + R_W_B_ * q, face});
    });
  }
}

// ---------------------------------------------------------------- Cylinder

Cylinder::Cylinder(const Eigen::Vector2d& center_xy, double z_min, double z_max, double radius)
    : center_(center_xy), z_min_(z_min), z_max_(z_max), radius_(radius) {
  face_material.assign(3, 0);
}

bool Cylinder::intersect(const Ray& ray, double t_max, ShapeHit* hit) const {
  const double ox = ray.origin.x() - center_.x(), oy = ray.origin.y() - center_.y();
  const double dx = ray.dir.x(), dy = ray.dir.y();
  double best = t_max;
  bool found = false;
  const double a = dx * dx + dy * dy;
  if (a > 1e-18) {
    // |o_xy + t d_xy|^2 = r^2.
    const double b = ox * dx + oy * dy;
    const double c = ox * ox + oy * oy - radius_ * radius_;
    const double disc = b * b - a * c;
    if (disc >= 0) {
      const double sq = std::sqrt(disc);
      for (const double t : {(-b - sq) / a, (-b + sq) / a}) {
        if (t <= kMinHitT || t > best) continue;
        const double z = ray.origin.z() + t * ray.dir.z();
        if (z < z_min_ - kEdgeTol || z > z_max_ + kEdgeTol) continue;
        const double x = ox + t * dx, y = oy + t * dy;
        double angle = std::atan2(y, x);
        if (angle < 0) angle += 2 * M_PI;
        best = t, found = true;
        hit->face = 0;
        hit->normal = Vec3(x, y, 0) / radius_;
        hit->uv = Eigen::Vector2d(angle * radius_, z - z_min_);
        break;
      }
    }
  }
  if (std::abs(ray.dir.z()) > 1e-15) {
    for (const int face : {1, 2}) {
      const double z_cap = face == 1 ? z_min_ : z_max_;
      const double t = (z_cap - ray.origin.z()) / ray.dir.z();
      if (t <= kMinHitT || t > best) continue;
      const double x = ox + t * dx, y = oy + t * dy;
      if (std::hypot(x, y) > radius_ + kEdgeTol) continue;
      best = t, found = true;
      hit->face = face;
      hit->normal = Vec3(0, 0, face == 1 ? -1.0 : 1.0);
      hit->uv = Eigen::Vector2d(x + radius_, y + radius_);
    }
  }
  if (found) hit->t = best;
  return found;
}

double Cylinder::distance(const Vec3& p) const {
  // Exact capped-cylinder SDF (Quilez) with the 2D distances (radial, axial).
  const double half_h = 0.5 * (z_max_ - z_min_);
  const double dr = (p.head<2>() - center_).norm() - radius_;
  const double dz = std::abs(p.z() - 0.5 * (z_min_ + z_max_)) - half_h;
  const double outside = std::hypot(std::max(dr, 0.0), std::max(dz, 0.0));
  return std::abs(outside + std::min(std::max(dr, dz), 0.0));
}

bool Cylinder::contains(const Vec3& p) const {
  return (p.head<2>() - center_).norm() <= radius_ + kContainTol && p.z() >= z_min_ - kContainTol &&
         p.z() <= z_max_ + kContainTol;
}

Eigen::AlignedBox3d Cylinder::bounds() const {
  return Eigen::AlignedBox3d(Vec3(center_.x() - radius_, center_.y() - radius_, z_min_),
                             Vec3(center_.x() + radius_, center_.y() + radius_, z_max_));
}

void Cylinder::sample(double spacing_m, std::vector<SurfacePoint>* out) const {
  for_each_grid_point(2 * M_PI * radius_, z_max_ - z_min_, spacing_m, [&](double u, double v) {
    const double angle = u / radius_;
    out->push_back({Vec3(center_.x() + radius_ * std::cos(angle), center_.y() + radius_ * std::sin(angle),
                         z_min_ + v), 0});
  });
  for_each_grid_point(2 * radius_, 2 * radius_, spacing_m, [&](double u, double v) {
    const double x = u - radius_, y = v - radius_;
    if (x * x + y * y > radius_ * radius_) return;
    out->push_back({Vec3(center_.x() + x, center_.y() + y, z_min_), 1});
    out->push_back({Vec3(center_.x() + x, center_.y() + y, z_max_), 2});
  });
}

// ---------------------------------------------------------------- Quad

Quad::Quad(const Vec3& corner_W, const Vec3& axis_u, double size_u, const Vec3& axis_v, double size_v,
           bool solid_below)
    : corner_(corner_W),
      axis_u_(axis_u.normalized()),
      axis_v_(axis_v.normalized()),
      normal_(axis_u.cross(axis_v).normalized()),
      size_u_(size_u),
      size_v_(size_v),
      solid_below_(solid_below) {
  face_material.assign(1, 0);
  if (solid_below_ && normal_.z() < 0) normal_ = -normal_;
}

bool Quad::intersect(const Ray& ray, double t_max, ShapeHit* hit) const {
  const double denom = ray.dir.dot(normal_);
  if (std::abs(denom) < 1e-15) return false;
  const double t = (corner_ - ray.origin).dot(normal_) / denom;
  if (t <= kMinHitT || t > t_max) return false;
  const Vec3 r = ray.origin + t * ray.dir - corner_;
  const double u = r.dot(axis_u_), v = r.dot(axis_v_);
  if (u < -kEdgeTol || u > size_u_ + kEdgeTol || v < -kEdgeTol || v > size_v_ + kEdgeTol) return false;
  hit->t = t;
  hit->face = 0;
  hit->normal = normal_;
  hit->uv = Eigen::Vector2d(u, v);
  return true;
}

double Quad::distance(const Vec3& p) const {
  const Vec3 r = p - corner_;
  const double u = r.dot(axis_u_), v = r.dot(axis_v_);
  const double du = std::max({-u, u - size_u_, 0.0}), dv = std::max({-v, v - size_v_, 0.0});
  return std::sqrt(du * du + dv * dv + std::pow(r.dot(normal_), 2));
}

bool Quad::contains(const Vec3& p) const {
  if (!solid_below_) return false;
  const Vec3 r = p - corner_;
  const double u = r.dot(axis_u_), v = r.dot(axis_v_);
  return r.dot(normal_) <= kContainTol && u >= -kContainTol && u <= size_u_ + kContainTol && v >= -kContainTol &&
         v <= size_v_ + kContainTol;
}

Eigen::AlignedBox3d Quad::bounds() const {
  Eigen::AlignedBox3d box(corner_);
  box.extend(corner_ + size_u_ * axis_u_);
  box.extend(corner_ + size_v_ * axis_v_);
  box.extend(corner_ + size_u_ * axis_u_ + size_v_ * axis_v_);
  return box;
}

void Quad::sample(double spacing_m, std::vector<SurfacePoint>* out) const {
  for_each_grid_point(size_u_, size_v_, spacing_m,
                      [&](double u, double v) { out->push_back({corner_ + u * axis_u_ + v * axis_v_, 0}); });
}

}  // namespace vilslam::sim
