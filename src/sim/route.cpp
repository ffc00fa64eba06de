#include "sim/route.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace vilslam::sim {
namespace {

double cross2(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }

double turning_angle(const Eigen::Vector2d& d_in, const Eigen::Vector2d& d_out) {
  return std::atan2(std::abs(cross2(d_in, d_out)), d_in.dot(d_out));
}

// Resamples the closed dense polyline (last point joins the first) at n equal arc-length steps.
std::vector<Vec3> resample_closed(const std::vector<Eigen::Vector2d>& dense, double step_m, double z) {
  std::vector<double> cumulative(dense.size() + 1, 0.0);
  for (std::size_t i = 0; i < dense.size(); ++i) {
    cumulative[i + 1] = cumulative[i] + (dense[(i + 1) % dense.size()] - dense[i]).norm();
  }
  const double length = cumulative.back();
  const int n = std::max(3, static_cast<int>(std::lround(length / step_m)));
  std::vector<Vec3> out;
  out.reserve(n + 1);
  std::size_t seg = 0;
  for (int k = 0; k < n; ++k) {
    const double s = length * k / n;
    while (cumulative[seg + 1] < s) ++seg;
    const double seg_len = cumulative[seg + 1] - cumulative[seg];
    const double alpha = seg_len > 0 ? (s - cumulative[seg]) / seg_len : 0.0;
    const Eigen::Vector2d p = (1 - alpha) * dense[seg] + alpha * dense[(seg + 1) % dense.size()];
    out.emplace_back(p.x(), p.y(), z);
  }
  out.push_back(out.front());
  return out;
}

}  // namespace

std::vector<Vec3> rounded_loop(const Polygon2& corners, double radius_m, double step_m, double z) {
  const std::size_t n = corners.size();
  std::vector<Eigen::Vector2d> dense;
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector2d& c = corners[i];
    const Eigen::Vector2d d_in = (c - corners[(i + n - 1) % n]).normalized();
    const Eigen::Vector2d d_out = (corners[(i + 1) % n] - c).normalized();
    const double angle = turning_angle(d_in, d_out);
    if (angle < 1e-9) {
      dense.push_back(c);
      continue;
    }
    // The arc is tangent to both edges at distance r tan(angle / 2) from the corner.
    const double tangent = radius_m * std::tan(0.5 * angle);
    const double side = cross2(d_in, d_out) > 0 ? 1.0 : -1.0;
    const Eigen::Vector2d start = c - tangent * d_in;
    const Eigen::Vector2d center = start + side * radius_m * Eigen::Vector2d(-d_in.y(), d_in.x());
    const Eigen::Vector2d arm = start - center;
    const int pieces = std::max(4, static_cast<int>(std::ceil(angle * radius_m / 0.02)));
    for (int k = 0; k <= pieces; ++k) {
      const double a = side * angle * k / pieces;
      dense.push_back(center + Eigen::Rotation2Dd(a) * arm);
    }
  }
  return resample_closed(dense, step_m, z);
}

Polygon2 start_mid_longest_edge(const Polygon2& corners) {
  const std::size_t n = corners.size();
  const auto edge_length = [&](std::size_t i) { return (corners[(i + 1) % n] - corners[i]).norm(); };
  std::size_t longest = 0;
  for (std::size_t i = 1; i < n; ++i) {
    if (edge_length(i) > edge_length(longest)) longest = i;
  }
  Polygon2 out = {0.5 * (corners[longest] + corners[(longest + 1) % n])};
  for (std::size_t k = 1; k <= n; ++k) out.push_back(corners[(longest + k) % n]);
  return out;
}

double rounded_loop_length(const Polygon2& corners, double radius_m) {
  const std::size_t n = corners.size();
  double length = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector2d d_in = corners[i] - corners[(i + n - 1) % n];
    const Eigen::Vector2d d_out = corners[(i + 1) % n] - corners[i];
    const double angle = turning_angle(d_in.normalized(), d_out.normalized());
    length += d_out.norm() - (2 * radius_m * std::tan(0.5 * angle) - radius_m * angle);
  }
  return length;
}

void scale_to_length(Polygon2* corners, double radius_m, double length_m) {
  // Rounding takes a fixed length per corner, independent of the scale.
  const double corner_loss = rounded_loop_length(*corners, radius_m) - rounded_loop_length(*corners, 0.0);
  const double scale = (length_m - corner_loss) / rounded_loop_length(*corners, 0.0);
  for (auto& c : *corners) c *= scale;
}

std::vector<Vec3> varied_route(const std::vector<Vec3>& route_W, double start_fraction, double lateral_m) {
  if (start_fraction == 0.0 && lateral_m == 0.0) return route_W;
  const std::size_t n = route_W.size() - 1;  // distinct waypoints (first == last)
  std::vector<Vec3> shifted(n);
  for (std::size_t i = 0; i < n; ++i) {
    // The horizontal direction of travel at waypoint i, from its two neighbours on the closed route.
    const Vec3 along = route_W[(i + 1) % n] - route_W[(i + n - 1) % n];
    const Vec3 left = Vec3(-along.y(), along.x(), 0.0).normalized();
    shifted[i] = route_W[i] + lateral_m * left;
  }
  std::vector<double> cumulative(n + 1, 0.0);
  for (std::size_t i = 0; i < n; ++i) cumulative[i + 1] = cumulative[i] + (shifted[(i + 1) % n] - shifted[i]).norm();
  const double s = start_fraction * cumulative[n];
  std::size_t k = 0;
  while (k + 1 < n && cumulative[k + 1] <= s) ++k;
  const double alpha = (s - cumulative[k]) / (cumulative[k + 1] - cumulative[k]);
  const Vec3 start = (1.0 - alpha) * shifted[k] + alpha * shifted[(k + 1) % n];
  std::vector<Vec3> out = {start};
  for (std::size_t j = 1; j <= n; ++j) {
    const Vec3& p = shifted[(k + j) % n];
    if ((p - out.back()).norm() > 1e-9) out.push_back(p);
  }
  if ((out.back() - start).norm() > 1e-9) out.push_back(start);
  out.back() = start;
  return out;
}

double polyline_length(const std::vector<Vec3>& points) {
  double length = 0;
  for (std::size_t i = 1; i < points.size(); ++i) length += (points[i] - points[i - 1]).norm();
  return length;
}

double route_clearance(const std::vector<Vec3>& route_W, const Shape& shape) {
  double best = std::numeric_limits<double>::infinity();
  for (const Vec3& p : route_W) best = std::min(best, shape.distance(p));
  return best;
}

Polygon2 rectilinear_loop(Rng& rng, double width, double depth, int max_notches, double min_notch) {
  const Polygon2 rect = {{0, 0}, {width, 0}, {width, depth}, {0, depth}};
  std::vector<bool> notched(4, false);
  const int notches = max_notches > 0 ? rng.integer(1, std::min(max_notches, 4)) : 0;
  for (int k = 0; k < notches; ++k) {
    int corner = rng.integer(0, 3);
    while (notched[corner]) corner = (corner + 1) % 4;
    notched[corner] = true;
  }
  Polygon2 loop;
  for (int i = 0; i < 4; ++i) {
    const Eigen::Vector2d& c = rect[i];
    if (!notched[i]) {
      loop.push_back(c);
      continue;
    }
    // Cut a rectangle out of the corner: back along the incoming edge, in, then out along the outgoing edge.
    const Eigen::Vector2d in = c - rect[(i + 3) % 4], out = rect[(i + 1) % 4] - c;
    const double a = rng.uniform(min_notch, std::max(min_notch, 0.4 * in.norm()));
    const double b = rng.uniform(min_notch, std::max(min_notch, 0.4 * out.norm()));
    const Eigen::Vector2d p1 = c - a * in.normalized();
    loop.push_back(p1);
    loop.push_back(p1 + b * out.normalized());
    loop.push_back(c + b * out.normalized());
  }
  return loop;
}

}  // namespace vilslam::sim
