#pragma once
// Geometric primitives of the simulated world. Each one answers a ray query (nearest hit with face,
// outward normal and continuous uv in metres), an exact unsigned distance, a solid containment test,
// its bounds and a grid sampling of its faces.
#include <cstdint>
#include <vector>

#include <Eigen/Geometry>

#include "common/lie.h"

namespace vilslam::sim {

struct Ray {
  Vec3 origin;
  Vec3 dir;  // unit
};

struct ShapeHit {
  double t = 0;
  Vec3 normal;  // unit outward normal of the face (not yet turned towards the ray origin)
  Eigen::Vector2d uv;
  int face = 0;
};

struct SurfacePoint {
  Vec3 p;
  int face = 0;
};

// A rectangle in the uv coordinates of one face that shows another material (doors, posters, signs).
struct Decal {
  int face = 0;
  Eigen::AlignedBox2d uv_box;
  int material = 0;
};

// Hits closer than this to the ray origin are ignored (rays that start on a surface).
constexpr double kMinHitT = 1e-9;
// Faces accept hits this far (m) outside their edges, so a ray through the edge shared by two faces
// never slips between them through rounding.
constexpr double kEdgeTol = 1e-7;

class Shape {
 public:
  virtual ~Shape() = default;
  // Nearest hit with t in (kMinHitT, t_max]; false when there is none.
  virtual bool intersect(const Ray& ray, double t_max, ShapeHit* hit) const = 0;
  virtual double distance(const Vec3& p) const = 0;
  // True when p is inside the solid or on its boundary (within 1e-6 m): surface points there are hidden.
  virtual bool contains(const Vec3& p) const = 0;
  virtual Eigen::AlignedBox3d bounds() const = 0;
  // Points on every face, about spacing_m apart (cell centres of a regular grid per face).
  virtual void sample(double spacing_m, std::vector<SurfacePoint>* out) const = 0;

  // The material of a face at uv: the last decal covering uv, else the face's own material.
  int material_at(int face, const Eigen::Vector2d& uv) const;

  std::vector<int> face_material;  // one per face
  std::vector<Decal> decals;
  Eigen::Vector2d uv_offset = Eigen::Vector2d::Zero();  // added to every uv so equal materials differ
};

// A box with half extents `half` in its own frame, placed by R_W_B and its centre.
// Faces 0..5: -x, +x, -y, +y, -z, +z. uv on x faces (y, z), on y faces (x, z), on z faces (x, y),
// measured from the box corner, so v is the height above the bottom on vertical faces.
class Box : public Shape {
 public:
  Box(const Vec3& center_W, const Mat3& R_W_B, const Vec3& half);
  static Box axis_aligned(const Vec3& min_W, const Vec3& max_W);
  bool intersect(const Ray& ray, double t_max, ShapeHit* hit) const override;
  double distance(const Vec3& p) const override;
  bool contains(const Vec3& p) const override;
  Eigen::AlignedBox3d bounds() const override;
  void sample(double spacing_m, std::vector<SurfacePoint>* out) const override;

 private:
  Vec3 center_;
  Mat3 R_W_B_;
  Vec3 half_;
  bool aligned_;  // R_W_B is the identity: skip the rotations
};

// A vertical capped cylinder. Faces: 0 side (u = arc length from +x, v = z - z_min), 1 bottom, 2 top.
class Cylinder : public Shape {
 public:
  Cylinder(const Eigen::Vector2d& center_xy, double z_min, double z_max, double radius);
  bool intersect(const Ray& ray, double t_max, ShapeHit* hit) const override;
  double distance(const Vec3& p) const override;
  bool contains(const Vec3& p) const override;
  Eigen::AlignedBox3d bounds() const override;
  void sample(double spacing_m, std::vector<SurfacePoint>* out) const override;

 private:
  Eigen::Vector2d center_;
  double z_min_, z_max_, radius_;
};

// A planar rectangle (walls, floors, ceilings, sloped ground): corner + size_u * axis_u + size_v * axis_v.
// uv is measured from the corner. A quad marked solid_below hides what lies under it (ground).
class Quad : public Shape {
 public:
  Quad(const Vec3& corner_W, const Vec3& axis_u, double size_u, const Vec3& axis_v, double size_v,
       bool solid_below = false);
  bool intersect(const Ray& ray, double t_max, ShapeHit* hit) const override;
  double distance(const Vec3& p) const override;
  bool contains(const Vec3& p) const override;
  Eigen::AlignedBox3d bounds() const override;
  void sample(double spacing_m, std::vector<SurfacePoint>* out) const override;

 private:
  Vec3 corner_, axis_u_, axis_v_, normal_;
  double size_u_, size_v_;
  bool solid_below_;
};

// A straight arched tunnel seen from inside: a circular vault of `radius` around a horizontal axis,
// cut by a flat floor `axis_height` below the axis, closed by two end caps. The axis starts at
// start_W (on the axis) and runs `length` along the horizontal direction of `yaw`.
// Faces: 0 vault (u = along the axis, v = arc length from the floor edge), 1 floor, 2 start cap, 3 end cap.
class ArchedTube : public Shape {
 public:
  ArchedTube(const Vec3& start_W, double yaw, double length, double radius, double axis_height);
  bool intersect(const Ray& ray, double t_max, ShapeHit* hit) const override;
  double distance(const Vec3& p) const override;
  bool contains(const Vec3&) const override { return false; }
  Eigen::AlignedBox3d bounds() const override;
  void sample(double spacing_m, std::vector<SurfacePoint>* out) const override;
  double floor_half_width() const;

 private:
  Vec3 to_local(const Vec3& p_W) const;
  Vec3 start_;
  Mat3 R_W_T_;  // tunnel frame: x along the axis, z up
  double length_, radius_, axis_height_;
};

}  // namespace vilslam::sim
