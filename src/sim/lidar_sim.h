#pragma once
// A multi-beam LiDAR, spinning (VLP-16 by default) or non-repetitive: every point is measured from the
// sensor pose at its own instant, so motion distorts the sweep as it does a real one.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "common/lie.h"
#include "common/types.h"
#include "sim/lidar_returns.h"
#include "sim/world.h"

namespace vilslam::sim {

enum class LidarPattern {
  kSpinning,        // rings of beams swept in azimuth; points carry their ring
  kNonRepetitive,   // no rings: heads trace zigzags that never repeat (Livox style); points carry no ring
};

// The non-repetitive pattern (lidar_beams.h): `heads` lasers fire together, spread evenly in azimuth and
// turning at rotation_hz, while their elevation sweeps the field of view as a triangle wave at
// oscillation_hz. An oscillation frequency that is no multiple of the sweep rate shifts the zigzags from
// one sweep to the next, so the covered directions grow with integration time, as on a Livox sensor.
struct NonRepetitiveConfig {
  int heads = 4;
  double points_per_second = 200000.0;
  double rotation_hz = 2.5;          // 4 heads x 90 deg per 0.1 s sweep: the whole circle each sweep
  double oscillation_hz = 441.8034;  // ~1 deg between strokes and ~1 deg along them at 200k points/s
};

struct LidarSimConfig {
  std::string sensor = "vlp16";       // the name of the model (lidar_sensor), for reports
  LidarPattern pattern = LidarPattern::kSpinning;
  int num_rings = 16;                 // spinning: beams per column
  double min_elevation_deg = -15.0;   // the field of view; spinning beams evenly spaced over it unless
  double max_elevation_deg = 15.0;    // beam_elevations_deg lists them (lowest first, num_rings values)
  std::vector<double> beam_elevations_deg;
  double azimuth_step_deg = 0.2;      // spinning
  NonRepetitiveConfig non_repetitive;
  double rate_hz = 10.0;
  double min_range_m = 0.5;
  double max_range_m = 100.0;
  double range_noise_sigma_m = 0.02;
  LidarReturnModel returns;           // missed echoes, oblique footprints, mixed pixels (ideal unless set)
};

// The sensors the simulator models (docs/simulator.md): "vlp16" (the default config), "hesai128" (128
// spinning beams, non-uniform: 0.125 deg apart around the horizon, like a Hesai Pandar128) and "mid360"
// (non-repetitive, 360 x 59 deg, like a Livox Mid-360). Throws std::invalid_argument on another name.
LidarSimConfig lidar_sensor(const std::string& name);

// One sweep starting at t_start_ns; T_W_L(t) gives the LiDAR pose at any instant. Points are in the
// LiDAR frame at their own instant, with t_offset_s, intensity (reflectivity and incidence) and, for a
// spinning sensor, ring (has_ring false for a non-repetitive one).
// The noise is a pure function of noise_seed.
LidarScan simulate_sweep(const World& world, const LidarSimConfig& config, TimeNs t_start_ns,
                         const std::function<SE3(TimeNs)>& T_W_L, std::uint64_t noise_seed);

}  // namespace vilslam::sim
