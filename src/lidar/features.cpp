#include "lidar/features.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include "lidar/ring_normals.h"

namespace vilslam::lidar {

namespace {

// One ring's points in azimuth order with their smoothness and selection state.
struct RingPoints {
  std::vector<Eigen::Vector3f> p;
  std::vector<float> range;
  std::vector<float> t_offset_s;
  std::vector<float> smoothness;
  std::vector<std::uint8_t> usable;  // 0 once rejected or taken (or suppressed by a taken neighbour)
};

RingPoints gather(const LidarScan& scan, const std::vector<std::uint32_t>& indices) {
  RingPoints ring;
  ring.p.reserve(indices.size());
  for (const std::uint32_t i : indices) {
    const LidarPoint& q = scan.points[i];
    ring.p.emplace_back(q.x, q.y, q.z);
    ring.range.push_back(ring.p.back().norm());
    ring.t_offset_s.push_back(q.t_offset_s);
  }
  ring.smoothness.assign(indices.size(), 0.0f);
  ring.usable.assign(indices.size(), 0);
  return ring;
}

// LOAM eq. (1): c = |sum_j (X_i - X_j)| / (|S| |X_i|), over the half_window neighbours on each side; the
// window sums come from prefix sums (in double, so that they do not lose precision along the ring).
void compute_smoothness(RingPoints& ring, int half_window) {
  const int n = static_cast<int>(ring.p.size());
  std::vector<Vec3> prefix(static_cast<std::size_t>(n) + 1, Vec3::Zero());
  for (int i = 0; i < n; ++i) prefix[i + 1] = prefix[i] + ring.p[i].cast<double>();
  const double count = 2.0 * half_window + 1.0;
  for (int i = half_window; i < n - half_window; ++i) {
    const Vec3 window = prefix[i + half_window + 1] - prefix[i - half_window];
    const Vec3 sum = count * ring.p[i].cast<double>() - window;
    ring.smoothness[i] = static_cast<float>(sum.norm() / (2.0 * half_window * ring.range[i]));
    ring.usable[i] = 1;
  }
}

// The range noise of point i: the sensor's, and the spread of a beam's footprint on an oblique surface,
// 0.5 r divergence tan(incidence). The incidence comes from the ring's chord over the window, t: the
// beam u grazes a surface along which the ring runs, sin(incidence) = |u . t| (tan capped at 10, 84 deg,
// beyond which max_neighbor_gap_ratio rejects the point anyway). The chord sees only the ring's own
// direction: a floor under a downward beam reads as head-on.
double range_sigma_m(const RingPoints& ring, int i, const FeatureConfig& config) {
  if (!(config.beam_divergence_rad > 0)) return config.range_noise_sigma_m;
  const int w = config.half_window;
  const Eigen::Vector3f chord = ring.p[i + w] - ring.p[i - w];
  const float chord_m = chord.norm();
  if (!(chord_m > 0)) return config.range_noise_sigma_m;
  const double sin_incidence = std::min(1.0, std::abs(static_cast<double>(ring.p[i].dot(chord)) / (ring.range[i] * chord_m)));
  const double cos_incidence = std::sqrt(1.0 - sin_incidence * sin_incidence);
  const double tan_incidence = cos_incidence > 0.1 * sin_incidence ? sin_incidence / cos_incidence : 10.0;
  return std::hypot(config.range_noise_sigma_m, 0.5 * ring.range[i] * config.beam_divergence_rad * tan_incidence);
}

// Smoothness std that range noise alone gives a point on a plane, at range_m: X_i carries 2w times its
// noise, each neighbour once, so |sum_j (X_i - X_j)| ~ sqrt(2w (2w + 1)) sigma and c ~ that / (2w r).
float noise_smoothness(float range_m, double sigma_m, int half_window) {
  const double w2 = 2.0 * half_window;
  return static_cast<float>(std::sqrt(w2 * (w2 + 1.0)) * sigma_m / (w2 * range_m));
}

// LOAM Sec. V-A rejections: points on surfaces nearly parallel to the beam (both neighbours far away
// relative to the range) and points on the far side of an occlusion boundary.
void reject_unreliable(RingPoints& ring, const FeatureConfig& config) {
  const int n = static_cast<int>(ring.p.size());
  const int w = config.half_window;
  const float gap_ratio = static_cast<float>(config.max_neighbor_gap_ratio);
  for (int i = 1; i + 1 < n; ++i) {
    const float limit = gap_ratio * ring.range[i];
    if ((ring.p[i + 1] - ring.p[i]).norm() > limit && (ring.p[i] - ring.p[i - 1]).norm() > limit) ring.usable[i] = 0;
  }
  for (int i = 0; i + 1 < n; ++i) {
    const float near = std::min(ring.range[i], ring.range[i + 1]);
    if (std::abs(ring.range[i] - ring.range[i + 1]) <= config.occlusion_jump_ratio * near) continue;
    // The farther side may be occluded by the nearer object: its points next to the boundary are not edges.
    const bool far_is_left = ring.range[i] > ring.range[i + 1];
    const int first = far_is_left ? std::max(0, i - w) : i + 1;
    const int last = far_is_left ? i : std::min(n - 1, i + 1 + w);
    for (int j = first; j <= last; ++j) ring.usable[j] = 0;
  }
}

// Marks the taken point and its neighbours within half_window along the ring as no longer selectable,
// stopping at a gap so that points across a discontinuity stay available.
void suppress_neighbours(RingPoints& ring, int i, int half_window, float max_gap_m) {
  ring.usable[i] = 0;
  const int n = static_cast<int>(ring.p.size());
  for (int step : {-1, 1}) {
    for (int k = 1; k <= half_window; ++k) {
      const int j = i + step * k;
      if (j < 0 || j >= n || (ring.p[j] - ring.p[j - step]).norm() > max_gap_m) break;
      ring.usable[j] = 0;
    }
  }
}

// Takes the sharpest usable points of ring[begin, end) as edges and the flattest as surfaces (LOAM Sec. V-A);
// a surface carries the normal that surface_normal(i) gives it.
template <typename SurfaceNormal>
void select_in_sector(RingPoints& ring, int begin, int end, const FeatureConfig& config,
                      const SurfaceNormal& surface_normal, std::vector<FeaturePoint>& edges,
                      std::vector<FeaturePoint>& surfaces) {
  // Candidates in order of selection: sharpest edges first, flattest surfaces first (ties by position).
  std::vector<int> edge_candidates, surface_candidates;
  for (int i = begin; i < end; ++i) {
    if (!ring.usable[i]) continue;
    const float noise_floor = static_cast<float>(config.edge_noise_sigmas) *
                              noise_smoothness(ring.range[i], range_sigma_m(ring, i, config), config.half_window);
    const float edge_min = std::max(static_cast<float>(config.edge_min_smoothness), noise_floor);
    if (ring.smoothness[i] > edge_min) edge_candidates.push_back(i);
    if (ring.smoothness[i] < config.surface_max_smoothness) surface_candidates.push_back(i);
  }
  const auto sharper = [&](int a, int b) {
    return ring.smoothness[a] > ring.smoothness[b] || (ring.smoothness[a] == ring.smoothness[b] && a < b);
  };
  const auto flatter = [&](int a, int b) {
    return ring.smoothness[a] < ring.smoothness[b] || (ring.smoothness[a] == ring.smoothness[b] && a < b);
  };
  std::sort(edge_candidates.begin(), edge_candidates.end(), sharper);
  std::sort(surface_candidates.begin(), surface_candidates.end(), flatter);
  constexpr float kSuppressGapM = 0.2f;
  const auto take = [&](const std::vector<int>& candidates, int max_count, bool with_normal,
                        std::vector<FeaturePoint>& out) {
    int taken = 0;
    for (auto it = candidates.begin(); it != candidates.end() && taken < max_count; ++it) {
      if (!ring.usable[*it]) continue;
      out.push_back({ring.p[*it].cast<double>(), ring.t_offset_s[*it], ring.smoothness[*it],
                     with_normal ? surface_normal(*it) : Vec3::Zero()});
      suppress_neighbours(ring, *it, config.half_window, kSuppressGapM);
      ++taken;
    }
  };
  take(edge_candidates, config.max_edges_per_sector, false, edges);
  take(surface_candidates, config.max_surfaces_per_sector, true, surfaces);
}

// The windows of neighbouring rings give a surface point its normal when they lie within this many range
// sigmas (rms) of one plane with its own: three keeps a noisy plane (rms one sigma) and leaves out a crease.
constexpr double kNormalMaxThicknessSigmas = 3.0;

}  // namespace

FeatureMethod resolve_feature_method(const LidarScan& scan, const RingConfig& ring_config, FeatureMethod method) {
  if (method != FeatureMethod::kAuto) return method;
  constexpr double kMinFractionOnRings = 0.7;
  return scan.has_ring || fraction_on_rings(scan, ring_config) >= kMinFractionOnRings ? FeatureMethod::kRings
                                                                                       : FeatureMethod::kNeighbourhood;
}

FeatureScan extract_features(const LidarScan& scan, const RingConfig& ring_config, const FeatureConfig& given) {
  if (resolve_feature_method(scan, ring_config, given.method) == FeatureMethod::kNeighbourhood) {
    return extract_neighbourhood_features(scan, given.neighbourhood, given.range_noise_sigma_m, ring_config.min_range_m,
                                          ring_config.max_range_m);
  }
  FeatureScan features;
  features.t_ns = scan.t_ns;
  const int w = given.half_window;
  const Rings rings = assign_rings(scan, ring_config);
  // Beyond reference_rings rings the per-sector counts shrink in proportion (at least one of each).
  FeatureConfig config = given;
  const int num_rings = static_cast<int>(rings.size());
  if (num_rings > config.reference_rings) {
    const auto scaled = [&](int count) { return std::max(1, count * config.reference_rings / num_rings); };
    config.max_edges_per_sector = scaled(config.max_edges_per_sector);
    config.max_surfaces_per_sector = scaled(config.max_surfaces_per_sector);
  }
  std::vector<RingPoints> ring_points;
  ring_points.reserve(rings.size());
  std::vector<const std::vector<Eigen::Vector3f>*> curves;
  for (const std::vector<std::uint32_t>& indices : rings) {
    ring_points.push_back(gather(scan, indices));
    curves.push_back(&ring_points.back().p);
  }
  // Normals from twice the smoothness window: over +-5 samples the range noise tilts them by several degrees.
  std::optional<RingNormals> normals;
  if (config.ring_normals) normals.emplace(curves, 2 * w);
  for (int k = 0; k < num_rings; ++k) {
    RingPoints& ring = ring_points[k];
    const int n = static_cast<int>(ring.p.size());
    if (n < 2 * w + 2) continue;
    compute_smoothness(ring, w);
    reject_unreliable(ring, config);
    // A surface's normal where its neighbouring rings show its plane within range noise (ring_normals.h).
    const auto surface_normal = [&](int i) {
      return normals ? normals->normal(k, i, kNormalMaxThicknessSigmas * range_sigma_m(ring, i, config)) : Vec3::Zero();
    };
    const int span = n - 2 * w;
    for (int s = 0; s < config.sectors_per_ring; ++s) {
      const int begin = w + span * s / config.sectors_per_ring;
      const int end = w + span * (s + 1) / config.sectors_per_ring;
      select_in_sector(ring, begin, end, config, surface_normal, features.edges, features.surfaces);
    }
  }
  return features;
}

}  // namespace vilslam::lidar
