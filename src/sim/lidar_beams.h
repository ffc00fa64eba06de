#pragma once
// The firing pattern of a simulated LiDAR as columns of beams fired at one instant: for a spinning sensor a
// column is one azimuth step of all its rings; for a non-repetitive sensor it is one shot of all its heads.
#include <cmath>
#include <stdexcept>

#include "common/time.h"
#include "sim/lidar_sim.h"

namespace vilslam::sim {

inline void check_lidar_config(const LidarSimConfig& c) {
  const NonRepetitiveConfig& n = c.non_repetitive;
  const bool spinning_ok = c.num_rings >= 1 && c.num_rings <= 256 && c.azimuth_step_deg > 0 &&
                           c.azimuth_step_deg <= 90 &&
                           (c.beam_elevations_deg.empty() || static_cast<int>(c.beam_elevations_deg.size()) == c.num_rings);
  const bool non_repetitive_ok = n.heads >= 1 && n.heads <= 64 && n.points_per_second >= n.heads * c.rate_hz &&
                                 n.points_per_second <= 1e7 && n.rotation_hz >= 0 && n.oscillation_hz > 0;
  const bool ok = (c.pattern == LidarPattern::kSpinning ? spinning_ok : non_repetitive_ok) && c.rate_hz > 0 &&
                  c.min_range_m >= 0 && c.max_range_m > c.min_range_m && c.range_noise_sigma_m >= 0 &&
                  c.max_elevation_deg >= c.min_elevation_deg && std::abs(c.min_elevation_deg) < 90 &&
                  std::abs(c.max_elevation_deg) < 90;
  if (!ok) throw std::invalid_argument("LidarSimConfig: beams, heads, rates or ranges out of bounds");
}

inline int num_azimuths(const LidarSimConfig& c) { return static_cast<int>(std::lround(360.0 / c.azimuth_step_deg)); }

inline int num_columns(const LidarSimConfig& c) {
  if (c.pattern == LidarPattern::kSpinning) return num_azimuths(c);
  return static_cast<int>(std::lround(c.non_repetitive.points_per_second / c.rate_hz / c.non_repetitive.heads));
}

inline int beams_per_column(const LidarSimConfig& c) {
  return c.pattern == LidarPattern::kSpinning ? c.num_rings : c.non_repetitive.heads;
}

// Ring 0 is the lowest beam (as the Velodyne driver numbers them).
inline double ring_elevation_rad(const LidarSimConfig& c, int ring) {
  if (!c.beam_elevations_deg.empty()) return c.beam_elevations_deg[static_cast<std::size_t>(ring)] * M_PI / 180.0;
  const double span = c.max_elevation_deg - c.min_elevation_deg;
  const double deg = c.num_rings > 1 ? c.min_elevation_deg + span * ring / (c.num_rings - 1) : c.min_elevation_deg;
  return deg * M_PI / 180.0;
}

// Time of the column's firing after the start of the sweep.
inline TimeNs column_offset_ns(const LidarSimConfig& c, int column) {
  return static_cast<TimeNs>(std::llround(1e9 / c.rate_hz * column / num_columns(c)));
}

inline Vec3 direction_from_angles(double azimuth_rad, double elevation_rad) {
  return Vec3(std::cos(elevation_rad) * std::cos(azimuth_rad), std::cos(elevation_rad) * std::sin(azimuth_rad),
              std::sin(elevation_rad));
}

// Beam `beam` of column `column` of the sweep starting at sweep_start_ns. Spinning beams sweep
// counter-clockwise seen from above (+z of L), starting along +x, the same every sweep. Non-repetitive
// heads depend on the absolute firing time: head h is at azimuth 2 pi (rotation_hz t + h / heads) and at
// elevation mid + half_span * tri(oscillation_hz t + h / heads), tri a triangle wave of period 1 in [-1, 1].
inline Vec3 beam_direction_L(const LidarSimConfig& c, int beam, int column, TimeNs sweep_start_ns = 0) {
  if (c.pattern == LidarPattern::kSpinning) {
    return direction_from_angles(2.0 * M_PI * column / num_azimuths(c), ring_elevation_rad(c, beam));
  }
  const NonRepetitiveConfig& n = c.non_repetitive;
  // Phases in cycles from integer nanoseconds, reduced before scaling so that long sequences keep precision.
  const TimeNs t_ns = sweep_start_ns + column_offset_ns(c, column);
  const auto cycles = [t_ns](double hz) {
    const TimeNs second = 1'000'000'000;
    return std::fmod(hz * static_cast<double>(t_ns / second), 1.0) + hz * ns_to_s(t_ns % second);
  };
  const double head_phase = static_cast<double>(beam) / n.heads;
  const double osc = cycles(n.oscillation_hz) + head_phase;
  const double tri = 4.0 * std::abs(osc + 0.25 - std::floor(osc + 0.25) - 0.5) - 1.0;
  const double mid_deg = 0.5 * (c.max_elevation_deg + c.min_elevation_deg);
  const double half_deg = 0.5 * (c.max_elevation_deg - c.min_elevation_deg);
  return direction_from_angles(2.0 * M_PI * (cycles(n.rotation_hz) + head_phase), (mid_deg + half_deg * tri) * M_PI / 180.0);
}

}  // namespace vilslam::sim
