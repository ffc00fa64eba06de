#pragma once
// A bounding volume hierarchy over axis-aligned boxes (binned SAH build), with ordered ray traversal,
// nearest-distance branch and bound, and point queries. Queries are const and thread-safe.
#include <algorithm>
#include <cstdint>
#include <limits>
#include <vector>

#include <Eigen/Geometry>

#include "sim/shapes.h"

namespace vilslam::sim {

class Bvh {
 public:
  void build(const std::vector<Eigen::AlignedBox3d>& boxes);

  // Calls hit(index, t_max) -> new t_max for every item whose box the ray enters before t_max,
  // nearest boxes first. Returns the final t_max.
  template <typename HitFn>
  double raycast(const Ray& ray, double t_max, HitFn&& hit) const;

  // Calls dist(index) -> distance for items whose box is closer than the best so far; returns the best.
  template <typename DistFn>
  double nearest(const Eigen::Vector3d& p, DistFn&& dist) const;

  // Calls fn(index) for every item whose box contains p (within 1e-6).
  template <typename Fn>
  void for_each_containing(const Eigen::Vector3d& p, Fn&& fn) const;

 private:
  struct Node {
    Eigen::AlignedBox3d box;
    int first = 0;  // leaf: first item in order_; inner: index of the left child (right = left + 1)
    int count = 0;  // > 0 for a leaf
  };
  void build_node(const std::vector<Eigen::AlignedBox3d>& boxes, int index, int begin, int end, int depth);
  // Entry distance of the ray into the box, or +inf when it misses within t_max.
  static double entry(const Eigen::AlignedBox3d& box, const Eigen::Vector3d& origin, const Eigen::Vector3d& inv_dir,
                      double t_max);

  std::vector<Node> nodes_;
  std::vector<int> order_;
};

inline double Bvh::entry(const Eigen::AlignedBox3d& box, const Eigen::Vector3d& origin,
                         const Eigen::Vector3d& inv_dir, double t_max) {
  double t0 = 0, t1 = t_max;
  for (int a = 0; a < 3; ++a) {
    double ta = (box.min()[a] - origin[a]) * inv_dir[a];
    double tb = (box.max()[a] - origin[a]) * inv_dir[a];
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
  }
  return t0 <= t1 ? t0 : std::numeric_limits<double>::infinity();
}

template <typename HitFn>
double Bvh::raycast(const Ray& ray, double t_max, HitFn&& hit) const {
  if (nodes_.empty()) return t_max;
  // A zero direction component becomes a tiny one so the slab test never computes 0 * inf.
  Eigen::Vector3d inv_dir;
  for (int a = 0; a < 3; ++a) {
    const double d = ray.dir[a];
    inv_dir[a] = 1.0 / (std::abs(d) > 1e-30 ? d : 1e-30);
  }
  if (entry(nodes_[0].box, ray.origin, inv_dir, t_max) > t_max) return t_max;
  int stack[64];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node& node = nodes_[stack[--top]];
    if (node.count > 0) {
      for (int i = node.first; i < node.first + node.count; ++i) t_max = hit(order_[i], t_max);
      continue;
    }
    const int left = node.first, right = node.first + 1;
    const double t_left = entry(nodes_[left].box, ray.origin, inv_dir, t_max);
    const double t_right = entry(nodes_[right].box, ray.origin, inv_dir, t_max);
    // Push the far child first so the near one is visited first; entries are re-checked lazily
    // against the shrinking t_max when popped (the cost of one more slab test).
    const bool left_first = t_left <= t_right;
    const int near = left_first ? left : right, far = left_first ? right : left;
    const double t_near = std::min(t_left, t_right), t_far = std::max(t_left, t_right);
    if (t_far <= t_max) stack[top++] = far;
    if (t_near <= t_max) stack[top++] = near;
  }
  return t_max;
}

template <typename DistFn>
double Bvh::nearest(const Eigen::Vector3d& p, DistFn&& dist) const {
  double best = std::numeric_limits<double>::infinity();
  if (nodes_.empty()) return best;
  int stack[64];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node& node = nodes_[stack[--top]];
    if (node.box.exteriorDistance(p) >= best) continue;
    if (node.count > 0) {
      for (int i = node.first; i < node.first + node.count; ++i) best = std::min(best, dist(order_[i]));
      continue;
    }
    const int left = node.first, right = node.first + 1;
    const bool left_first = nodes_[left].box.exteriorDistance(p) <= nodes_[right].box.exteriorDistance(p);
    stack[top++] = left_first ? right : left;
    stack[top++] = left_first ? left : right;
  }
  return best;
}

template <typename Fn>
void Bvh::for_each_containing(const Eigen::Vector3d& p, Fn&& fn) const {
  if (nodes_.empty()) return;
  int stack[64];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node& node = nodes_[stack[--top]];
    if (node.box.exteriorDistance(p) > 1e-6) continue;
    if (node.count > 0) {
      for (int i = node.first; i < node.first + node.count; ++i) fn(order_[i]);
      continue;
    }
    stack[top++] = node.first;
    stack[top++] = node.first + 1;
  }
}

}  // namespace vilslam::sim
