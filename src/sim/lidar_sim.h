#pragma once
// A spinning multi-beam LiDAR (VLP-16 by default): every point is measured from the sensor pose at
// its own instant, so motion distorts the sweep as it does a real one.
#include <cstdint>
#include <functional>

#include "common/lie.h"
#include "common/types.h"
#include "sim/world.h"

namespace vilslam::sim {

struct LidarSimConfig {
  int num_rings = 16;
  double min_elevation_deg = -15.0;
  double max_elevation_deg = 15.0;
  double azimuth_step_deg = 0.2;
  double rate_hz = 10.0;
  double min_range_m = 0.5;
  double max_range_m = 100.0;
  double range_noise_sigma_m = 0.02;
};

// One sweep starting at t_start_ns; T_W_L(t) gives the LiDAR pose at any instant. Points are in the
// LiDAR frame at their own instant, with ring, t_offset_s and intensity (reflectivity and incidence).
// The noise is a pure function of noise_seed.
LidarScan simulate_sweep(const World& world, const LidarSimConfig& config, TimeNs t_start_ns,
                         const std::function<SE3(TimeNs)>& T_W_L, std::uint64_t noise_seed);

}  // namespace vilslam::sim
