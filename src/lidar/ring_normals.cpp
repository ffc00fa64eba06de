#include "lidar/ring_normals.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

namespace vilslam::lidar {

namespace {

// A cheap stand-in for atan2(y, x) with the same order over [-pi, pi): the "diamond angle" y / (|x| + |y|)
// on each half plane, mapped to [-2, 2]. Rings are in atan2 order, so their pseudo-angles ascend too.
float pseudo_azimuth(const Eigen::Vector3f& p) {
  const float l1 = std::abs(p.x()) + std::abs(p.y());
  if (!(l1 > 0.0f)) return 0.0f;
  const float d = p.y() / l1;
  if (p.x() >= 0.0f) return d;
  return p.y() >= 0.0f ? 2.0f - d : -2.0f - d;
}

// Sums of a window's points relative to an origin (the feature point, so that the scatter loses no precision).
struct WindowSums {
  double count = 0.0;
  Vec3 sum = Vec3::Zero();
  Eigen::Matrix3d outer = Eigen::Matrix3d::Zero();

  WindowSums& operator+=(const WindowSums& other) {
    count += other.count;
    sum += other.sum;
    outer += other.outer;
    return *this;
  }
};

WindowSums window_sums(const std::vector<Eigen::Vector3f>& ring, int first, int last, const Vec3& origin) {
  WindowSums s;
  for (int m = first; m <= last; ++m) {
    const Vec3 d = ring[m].cast<double>() - origin;
    s.count += 1.0;
    s.sum += d;
    s.outer += d * d.transpose();
  }
  return s;
}

// Plane fit (principal component analysis) of the summed windows: normal and rms thickness, or a zero normal
// when the points spread along one line only (their second axis within three thicknesses).
struct PlaneFit {
  Vec3 normal = Vec3::Zero();
  double thickness_m = 0.0;
};

PlaneFit fit_plane(const WindowSums& s) {
  const Vec3 mean = s.sum / s.count;
  const Eigen::Matrix3d scatter = s.outer / s.count - mean * mean.transpose();
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen;
  eigen.computeDirect(scatter);
  const Vec3 lambda = eigen.eigenvalues().cwiseMax(0.0);
  PlaneFit fit;
  fit.thickness_m = std::sqrt(lambda(0));
  if (std::sqrt(lambda(1)) > 3.0 * fit.thickness_m) fit.normal = eigen.eigenvectors().col(0).normalized();
  return fit;
}

}  // namespace

RingNormals::RingNormals(const std::vector<const std::vector<Eigen::Vector3f>*>& rings, int half_window)
    : rings_(rings), azimuth_(rings.size()), rank_(rings.size(), -1), half_window_(half_window) {
  std::vector<double> sin_elevation(rings.size(), 0.0);
  std::vector<int> order;
  for (std::size_t k = 0; k < rings.size(); ++k) {
    const std::vector<Eigen::Vector3f>& points = *rings[k];
    if (points.empty()) continue;
    azimuth_[k].reserve(points.size());
    for (const Eigen::Vector3f& p : points) {
      azimuth_[k].push_back(pseudo_azimuth(p));
      const float range = p.norm();
      if (range > 0.0f) sin_elevation[k] += p.z() / range;
    }
    sin_elevation[k] /= static_cast<double>(points.size());
    order.push_back(static_cast<int>(k));
  }
  // Ring numbers need not follow elevation (some drivers interleave their lasers): neighbours by elevation.
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return sin_elevation[a] < sin_elevation[b]; });
  for (std::size_t j = 0; j < order.size(); ++j) rank_[order[j]] = static_cast<int>(j);
  by_elevation_ = std::move(order);
}

int RingNormals::nearest_in_azimuth(int k, float azimuth, float tolerance) const {
  const std::vector<float>& azimuths = azimuth_[k];
  const auto it = std::lower_bound(azimuths.begin(), azimuths.end(), azimuth);
  int best = -1;
  float best_gap = tolerance;
  for (auto candidate : {it, it == azimuths.begin() ? it : it - 1}) {
    if (candidate == azimuths.end()) continue;
    const float gap = std::abs(*candidate - azimuth);
    if (gap <= best_gap) {
      best_gap = gap;
      best = static_cast<int>(candidate - azimuths.begin());
    }
  }
  return best;
}

Vec3 RingNormals::normal(int k, int i, double max_thickness_m) const {
  const std::vector<Eigen::Vector3f>& own = *rings_[k];
  const int w = half_window_;
  const std::vector<float>& azimuths = azimuth_[k];
  const Vec3 origin = own[i].cast<double>();
  const int first = std::max(0, i - w), last = std::min(static_cast<int>(own.size()) - 1, i + w);
  // A neighbouring ring's point counts when it lies within the own window's azimuth half-span.
  const float tolerance = 0.5f * (azimuths[last] - azimuths[first]);
  // The window of the ring `offset` places above (below, when negative) in elevation, centred on its point
  // nearest in azimuth; no count when there is none.
  const auto window = [&](int offset) {
    const int rank = rank_[k] + offset;
    if (rank < 0 || rank >= static_cast<int>(by_elevation_.size())) return WindowSums{};
    const int n = by_elevation_[rank];
    const int j = nearest_in_azimuth(n, azimuths[i], tolerance);
    if (j < 0) return WindowSums{};
    const std::vector<Eigen::Vector3f>& ring = *rings_[n];
    return window_sums(ring, std::max(0, j - w), std::min(static_cast<int>(ring.size()) - 1, j + w), origin);
  };
  const WindowSums own_sums = window_sums(own, first, last, origin);
  const WindowSums below = window(-1), above = window(1);
  // The own window and two neighbouring rings: a plane through two ring segments always exists (two nearly
  // parallel lines), but at a crease or an edge a third ring leaves it. One ring on each side first; where
  // those do not share a plane within max_thickness_m, the thinner of two above or two below, so that a point
  // next to a crease takes its normal from the rings on its own side.
  const auto fit = [&](const WindowSums& a, const WindowSums& b) {
    if (a.count == 0.0 || b.count == 0.0) return PlaneFit{};
    WindowSums sums = own_sums;
    sums += a;
    sums += b;
    PlaneFit plane = fit_plane(sums);
    return plane.thickness_m < max_thickness_m ? plane : PlaneFit{};
  };
  const PlaneFit across = fit(below, above);
  if (!across.normal.isZero()) return across.normal;
  // The second rings out only when the first two do not share the point's plane (near a crease or an edge).
  const PlaneFit upper = fit(above, window(2)), lower = fit(below, window(-2));
  if (upper.normal.isZero() || (!lower.normal.isZero() && lower.thickness_m < upper.thickness_m)) return lower.normal;
  return upper.normal;
}

}  // namespace vilslam::lidar
