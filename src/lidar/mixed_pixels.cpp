#include "lidar/mixed_pixels.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "common/point_index.h"
#include "lidar/ring_assignment.h"

namespace vilslam::lidar {

namespace {

constexpr double kTwoPi = 2.0 * M_PI;

double range_of(const LidarPoint& p) { return std::sqrt(double(p.x) * p.x + double(p.y) * p.y + double(p.z) * p.z); }

double azimuth_of(const LidarPoint& p) { return std::atan2(double(p.y), double(p.x)); }

void flag_ring(const LidarScan& scan, const std::vector<std::uint32_t>& ring, const MixedPixelConfig& config,
               std::vector<bool>& mixed) {
  const std::size_t n = ring.size();
  if (n < 3) return;
  std::vector<double> range(n), azimuth(n), step(n);  // step[k]: ring[k] to ring[(k + 1) % n], the last wrapping
  for (std::size_t k = 0; k < n; ++k) {
    range[k] = range_of(scan.points[ring[k]]);
    azimuth[k] = azimuth_of(scan.points[ring[k]]);
  }
  for (std::size_t k = 0; k < n; ++k) {
    const double d = azimuth[(k + 1) % n] - azimuth[k];
    step[k] = d < 0 ? d + kTwoPi : d;
  }
  std::vector<double> sorted = step;
  std::nth_element(sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(n / 2), sorted.end());
  const double max_step = config.max_step_ratio * sorted[n / 2];
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t prev = (k + n - 1) % n, next = (k + 1) % n;
    if (step[prev] > max_step || step[k] > max_step) continue;
    const double min_gap = config.min_gap_ratio * range[k];
    const double lo = std::min(range[prev], range[next]), hi = std::max(range[prev], range[next]);
    if (range[k] - lo > min_gap && hi - range[k] > min_gap) mixed[ring[k]] = true;
  }
}

// Without rings: a k-d tree over the beams' unit directions (chord length ~ angle). A point is mixed when its
// nearest beams include one nearer and one farther by more than the gap and none within the gap of its range: a
// point on a surface, even an oblique one, has neighbours along the surface's line of equal range.
void flag_by_direction(const LidarScan& scan, const MixedPixelConfig& config, std::vector<bool>& mixed) {
  std::vector<Eigen::Vector3f> directions;
  std::vector<std::uint32_t> ids;
  std::vector<double> ranges;
  for (std::uint32_t i = 0; i < scan.points.size(); ++i) {
    const LidarPoint& p = scan.points[i];
    const double r = range_of(p);
    if (!(r > 0.01) || !std::isfinite(r)) continue;
    directions.emplace_back(static_cast<float>(p.x / r), static_cast<float>(p.y / r), static_cast<float>(p.z / r));
    ids.push_back(i);
    ranges.push_back(r);
  }
  if (directions.size() < 3) return;
  const PointIndex index(directions);
  const double max_chord = 2.0 * std::sin(0.5 * config.max_neighbour_angle_deg * M_PI / 180.0);
  const float max_chord_sq = static_cast<float>(max_chord * max_chord);
  const double tan_incidence = std::tan(config.max_incidence_deg * M_PI / 180.0);
  for (std::size_t k = 0; k < ids.size(); ++k) {
    const double r = ranges[k];
    bool nearer = false, farther = false, level = false;
    for (const PointIndex::Neighbour& n :
         index.nearest_k(index.points()[k], static_cast<std::size_t>(config.direction_neighbours) + 1)) {
      if (n.index == k || n.dist_sq > max_chord_sq) continue;
      const double angle_rad = std::sqrt(static_cast<double>(n.dist_sq));  // the chord, for small angles
      const double gap = r * std::max(config.min_gap_ratio, tan_incidence * angle_rad);
      const double dr = ranges[n.index] - r;
      nearer |= dr < -gap;
      farther |= dr > gap;
      level |= std::abs(dr) <= gap;
    }
    if (nearer && farther && !level) mixed[ids[k]] = true;
  }
}

}  // namespace

std::vector<bool> mixed_pixels(const LidarScan& scan, const MixedPixelConfig& config) {
  std::vector<bool> mixed(scan.points.size(), false);
  if (!scan.has_ring) {
    flag_by_direction(scan, config, mixed);
    return mixed;
  }
  RingConfig all_ranges;
  all_ranges.min_range_m = 0.01;  // returns at the origin (no echo) are no neighbours
  all_ranges.max_range_m = std::numeric_limits<double>::infinity();
  for (const std::vector<std::uint32_t>& ring : assign_rings(scan, all_ranges)) flag_ring(scan, ring, config, mixed);
  return mixed;
}

}  // namespace vilslam::lidar
