#pragma once
// The firing pattern of a spinning multi-beam LiDAR: ring elevations, azimuth steps and firing times.
#include <cmath>
#include <stdexcept>

#include "common/time.h"
#include "sim/lidar_sim.h"

namespace vilslam::sim {

inline void check_lidar_config(const LidarSimConfig& c) {
  const bool ok = c.num_rings >= 1 && c.num_rings <= 256 && c.azimuth_step_deg > 0 && c.azimuth_step_deg <= 90 &&
                  c.rate_hz > 0 && c.min_range_m >= 0 && c.max_range_m > c.min_range_m &&
                  c.range_noise_sigma_m >= 0 && c.max_elevation_deg >= c.min_elevation_deg &&
                  std::abs(c.min_elevation_deg) < 90 && std::abs(c.max_elevation_deg) < 90;
  if (!ok) throw std::invalid_argument("LidarSimConfig: rings, azimuth step, rate or ranges out of bounds");
}

inline int num_azimuths(const LidarSimConfig& c) { return static_cast<int>(std::lround(360.0 / c.azimuth_step_deg)); }

// Ring 0 is the lowest beam (as the Velodyne driver numbers them).
inline double ring_elevation_rad(const LidarSimConfig& c, int ring) {
  const double span = c.max_elevation_deg - c.min_elevation_deg;
  const double deg = c.num_rings > 1 ? c.min_elevation_deg + span * ring / (c.num_rings - 1) : c.min_elevation_deg;
  return deg * M_PI / 180.0;
}

// Beams sweep counter-clockwise seen from above (+z of L), starting along +x.
inline Vec3 beam_direction_L(const LidarSimConfig& c, int ring, int azimuth_index) {
  const double azimuth = 2.0 * M_PI * azimuth_index / num_azimuths(c);
  const double elevation = ring_elevation_rad(c, ring);
  return Vec3(std::cos(elevation) * std::cos(azimuth), std::cos(elevation) * std::sin(azimuth), std::sin(elevation));
}

// Time of the azimuth's firing after the start of the sweep.
inline TimeNs azimuth_offset_ns(const LidarSimConfig& c, int azimuth_index) {
  return static_cast<TimeNs>(std::llround(1e9 / c.rate_hz * azimuth_index / num_azimuths(c)));
}

}  // namespace vilslam::sim
