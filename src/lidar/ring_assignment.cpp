#include "lidar/ring_assignment.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace vilslam::lidar {

namespace {

constexpr double kRadToDeg = 180.0 / M_PI;

double ring_spacing_deg(const RingConfig& config) {
  return config.num_rings > 1 ? (config.max_elevation_deg - config.min_elevation_deg) / (config.num_rings - 1) : 1.0;
}

// The point's elevation in ring spacings above the lowest ring.
double ring_coordinate(const LidarPoint& p, const RingConfig& config) {
  const double elevation_deg = std::atan2(p.z, std::hypot(p.x, p.y)) * kRadToDeg;
  return (elevation_deg - config.min_elevation_deg) / ring_spacing_deg(config);
}

// Ring index from elevation, or -1 when the beam falls outside the configured fan (by over half a spacing).
int ring_from_elevation(const LidarPoint& p, const RingConfig& config) {
  const long ring = std::lround(ring_coordinate(p, config));
  return ring >= 0 && ring < config.num_rings ? static_cast<int>(ring) : -1;
}

bool in_range(const LidarPoint& p, const RingConfig& config) {
  const double range_sq = double(p.x) * p.x + double(p.y) * p.y + double(p.z) * p.z;
  return range_sq >= config.min_range_m * config.min_range_m && range_sq <= config.max_range_m * config.max_range_m;
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
  int num_rings = config.num_rings;
  if (scan.has_ring) {
    for (const LidarPoint& p : scan.points) num_rings = std::max(num_rings, p.ring + 1);
  }
  std::vector<std::vector<std::pair<float, std::uint32_t>>> by_ring(static_cast<std::size_t>(num_rings));
  for (std::uint32_t i = 0; i < scan.points.size(); ++i) {
    const LidarPoint& p = scan.points[i];
    if (!in_range(p, config)) continue;
    const int ring = scan.has_ring ? p.ring : ring_from_elevation(p, config);
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

double fraction_on_rings(const LidarScan& scan, const RingConfig& config) {
  std::size_t in = 0, on = 0;
  for (const LidarPoint& p : scan.points) {
    if (!in_range(p, config)) continue;
    ++in;
    const double c = ring_coordinate(p, config);
    on += ring_from_elevation(p, config) >= 0 && std::abs(c - std::round(c)) <= 0.25;
  }
  return in > 0 ? static_cast<double>(on) / static_cast<double>(in) : 0.0;
}

}  // namespace vilslam::lidar
