#include "lidar/ring_assignment.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace vilslam::lidar {

namespace {

constexpr double kRadToDeg = 180.0 / M_PI;

// Ring index from elevation, or -1 when the beam falls outside the configured fan (by over half a spacing).
int ring_from_elevation(const LidarPoint& p, const RingConfig& config) {
  const double elevation_deg = std::atan2(p.z, std::hypot(p.x, p.y)) * kRadToDeg;
  const double spacing_deg =
      config.num_rings > 1 ? (config.max_elevation_deg - config.min_elevation_deg) / (config.num_rings - 1) : 1.0;
  const long ring = std::lround((elevation_deg - config.min_elevation_deg) / spacing_deg);
  return ring >= 0 && ring < config.num_rings ? static_cast<int>(ring) : -1;
}

// Orders one ring by (azimuth, index). A spinning sensor delivers a ring already sorted up to one wrap-around,
// which a rotation fixes in linear time; anything else is sorted.
void sort_by_azimuth(std::vector<std::pair<float, std::uint32_t>>& ring) {
  const auto descent = std::is_sorted_until(ring.begin(), ring.end());
  if (descent != ring.end() && std::is_sorted(descent, ring.end()) && ring.back() <= ring.front()) {
    std::rotate(ring.begin(), descent, ring.end());
  }
  if (!std::is_sorted(ring.begin(), ring.end())) std::stable_sort(ring.begin(), ring.end());
}

}  // namespace

Rings assign_rings(const LidarScan& scan, const RingConfig& config) {
  std::vector<std::vector<std::pair<float, std::uint32_t>>> by_ring(static_cast<std::size_t>(config.num_rings));
  const double min_sq = config.min_range_m * config.min_range_m;
  const double max_sq = config.max_range_m * config.max_range_m;
  for (std::uint32_t i = 0; i < scan.points.size(); ++i) {
    const LidarPoint& p = scan.points[i];
    const double range_sq = double(p.x) * p.x + double(p.y) * p.y + double(p.z) * p.z;
    if (!(range_sq >= min_sq && range_sq <= max_sq)) continue;
    const int ring = scan.has_ring ? (p.ring < config.num_rings ? p.ring : -1) : ring_from_elevation(p, config);
    if (ring < 0) continue;
    by_ring[static_cast<std::size_t>(ring)].emplace_back(std::atan2(p.y, p.x), i);
  }
  Rings rings(by_ring.size());
  for (std::size_t r = 0; r < by_ring.size(); ++r) {
    sort_by_azimuth(by_ring[r]);
    rings[r].reserve(by_ring[r].size());
    for (const auto& entry : by_ring[r]) rings[r].push_back(entry.second);
  }
  return rings;
}

}  // namespace vilslam::lidar
