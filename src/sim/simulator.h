#pragma once
// The simulator: a world, a trajectory through it and the rig's sensors, written as a dataset in the
// project's folder format (with ground truth, the reference model and a KITTI copy of the scans).
#include <cstdint>
#include <functional>
#include <optional>
#include <string>

#include "sim/sim_config.h"
#include "sim/sim_report.h"
#include "sim/world.h"

namespace vilslam::sim {

struct SimulateRequest {
  Scenario scenario = Scenario::kHighbay;
  std::string out_dir;
  std::uint64_t seed = 0;
  std::optional<std::uint64_t> world_seed;  // builds the world from this, not seed: the same world, other noise
  double route_start = 0;       // start this fraction of the route's length along it, in [0, 1)
  double route_offset_m = 0;    // fly the route shifted sideways by this much (left of travel when positive)
  double length_m = 0;          // route length; 0: the scenario's preset (or what duration_s implies)
  double duration_s = 0;        // > 0: size the route so the closed trajectory lasts this long
  int laps = 1;                 // times round the world's route (the same world: only the time grows)
  bool preview = false;         // only the first config.preview_duration_s seconds, coarse model
  std::string trajectory_path;  // fly this ground truth (TUM) instead of the world's route
  std::string imu_path;         // use this real IMU stream (EuRoC imu0/data.csv) and its timestamps
  bool overwrite = false;
  bool report = false;          // also count corners and LiDAR degeneracy for the report
  // Optional: the share of the images and sweeps written so far, in [0, 1] (images first).
  std::function<void(double)> progress;
};

// Writes the dataset to request.out_dir (atomically: a partial folder renamed at the end) and returns
// what was written. Throws InputError on bad input files or an existing output without overwrite.
SequenceReport simulate(const SimConfig& config, const SimulateRequest& request);

}  // namespace vilslam::sim
