#include "lidar/sensor_traits.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>

#include "common/error.h"
#include "lidar/azimuth_times.h"

namespace vilslam::lidar {
namespace {

constexpr double kMinTraitRange_m = 1.0;  // nearer returns: the robot itself, mixed pixels
// Rings are told from the elevations of returns beyond this range: a laser's offset from the sensor's origin
// (a few cm) spreads its elevation by offset / range, about 0.3 deg at 5 m.
constexpr double kRingRange_m = 5.0;
constexpr double kElevationBinDeg = 0.05;
// The elevation bins that hold this share of the returns, when rings: a few bins around each laser.
constexpr double kDenseShare = 0.9;
// Rings fill at most this share of the elevation span's bins with the dense share of the returns: measured 0.065 on
// the real BALM sweeps (64 beams over 90 deg), 0.05 for a VLP-16; uniform elevations fill about 0.9, and the
// simulated Mid-360's zigzags, whose elevations repeat on a fine grid, 0.355.
constexpr double kMaxRingFill = 0.3;

double quantile(std::vector<double> values, double q) {
  const auto k = static_cast<std::size_t>(q * static_cast<double>(values.size() - 1));
  std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(k), values.end());
  return values[k];
}

// Laser rings in a histogram of elevations: the fewest bins holding the dense share of the returns, grouped into
// runs of adjacent bins, one run per laser. 0 when those bins fill more than kMaxRingFill of the span.
int rings_in(const std::vector<double>& elevations_deg, double min_elevation_deg, double max_elevation_deg) {
  if (elevations_deg.size() < SensorTraits::kMinPoints) return 0;
  const int bins = static_cast<int>(std::ceil((max_elevation_deg - min_elevation_deg) / kElevationBinDeg)) + 1;
  std::vector<std::size_t> count(static_cast<std::size_t>(bins), 0);
  std::size_t in_span = 0;
  for (const double e : elevations_deg) {
    const int b = static_cast<int>(std::floor((e - min_elevation_deg) / kElevationBinDeg));
    if (b < 0 || b >= bins) continue;
    ++count[static_cast<std::size_t>(b)];
    ++in_span;
  }
  std::vector<int> order(static_cast<std::size_t>(bins));
  for (int b = 0; b < bins; ++b) order[static_cast<std::size_t>(b)] = b;
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
    return count[static_cast<std::size_t>(a)] > count[static_cast<std::size_t>(b)];
  });
  std::vector<bool> dense(static_cast<std::size_t>(bins), false);
  std::size_t held = 0, dense_bins = 0;
  for (const int b : order) {
    if (static_cast<double>(held) >= kDenseShare * static_cast<double>(in_span)) break;
    dense[static_cast<std::size_t>(b)] = true;
    held += count[static_cast<std::size_t>(b)];
    ++dense_bins;
  }
  if (static_cast<double>(dense_bins) > kMaxRingFill * bins) return 0;
  int runs = 0;
  for (std::size_t b = 0; b < dense.size(); ++b) runs += dense[b] && (b == 0 || !dense[b - 1]);
  return runs;
}

}  // namespace

SensorTraits read_sensor_traits(const LidarScan& sweep) {
  SensorTraits t;
  t.ring_field = sweep.has_ring;
  t.point_times = has_point_times(sweep);
  std::vector<double> ranges, elevations_deg, far_elevations_deg;
  std::array<bool, 360> sector{};
  int max_ring = -1;
  for (const LidarPoint& p : sweep.points) {
    const double r = std::sqrt(double(p.x) * p.x + double(p.y) * p.y + double(p.z) * p.z);
    if (!std::isfinite(r) || r < kMinTraitRange_m) continue;
    ranges.push_back(r);
    const double elevation_deg = std::asin(p.z / r) * 180.0 / M_PI;
    elevations_deg.push_back(elevation_deg);
    if (r >= kRingRange_m) far_elevations_deg.push_back(elevation_deg);
    const double azimuth_deg = std::atan2(double(p.y), double(p.x)) * 180.0 / M_PI + 180.0;
    sector[static_cast<std::size_t>(std::min(359.0, std::floor(azimuth_deg)))] = true;
    max_ring = std::max(max_ring, static_cast<int>(p.ring));
  }
  t.points = ranges.size();
  if (!t.read()) {
    t.rings = t.ring_field ? max_ring + 1 : 0;
    return t;
  }
  t.min_elevation_deg = quantile(elevations_deg, 0.005);
  t.max_elevation_deg = quantile(elevations_deg, 0.995);
  t.azimuth_coverage = static_cast<double>(std::count(sector.begin(), sector.end(), true)) / 360.0;
  t.range_p10_m = quantile(ranges, 0.1);
  t.range_median_m = quantile(ranges, 0.5);
  t.range_p90_m = quantile(ranges, 0.9);
  t.range_max_m = quantile(ranges, 0.995);
  t.rings = t.ring_field ? max_ring + 1
                         : rings_in(far_elevations_deg, t.min_elevation_deg - 1.0, t.max_elevation_deg + 1.0);
  return t;
}

SensorTraits first_sweep_traits(const DatasetIndex& index) {
  if (index.scans.empty()) throw InputError(index.summary.path, "no LiDAR sweep to read the sensor's traits from");
  return read_sensor_traits(load_scan(index, 0));
}

std::string sensor_traits_text(const SensorTraits& t) {
  if (!t.read()) {
    return "lidar_points: " + std::to_string(t.points) + " (too few to read the sensor's traits)\nlidar_ring_field: " +
           (t.ring_field ? "yes" : "no") + "\nlidar_point_times: " + (t.point_times ? "yes" : "no") + "\n";
  }
  char text[640];
  std::snprintf(text, sizeof text,
                "lidar_points: %zu\nlidar_ring_field: %s\nlidar_rings: %d (%s)\nlidar_point_times: %s\n"
                "lidar_elevation_deg: %.1f to %.1f\nlidar_azimuth_coverage: %.2f\n"
                "lidar_range_m: p10 %.2f, median %.2f, p90 %.2f, max %.2f\n",
                t.points, t.ring_field ? "yes" : "no", t.rings,
                t.spinning() ? "a spinning head" : "none: a non-repetitive pattern",
                t.point_times ? "yes" : "no", t.min_elevation_deg, t.max_elevation_deg, t.azimuth_coverage,
                t.range_p10_m, t.range_median_m, t.range_p90_m, t.range_max_m);
  return text;
}

}  // namespace vilslam::lidar
