#pragma once
// Deterministic offline mode (paper, system overview): the dataset is read as one time-ordered event
// stream; IMU samples go to the VIO, stereo pairs through the visual frontend into the VIO. Collects the
// camera-rate optimized states, the IMU-rate propagated poses and per-module timings.
#include <vector>

#include "common/types.h"
#include "frontend/frontend_config.h"
#include "io/dataset.h"
#include "vio/vio.h"

namespace vilslam {

struct OfflineRunConfig {
  FrontendConfig frontend;
  VioConfig vio;
};

struct OfflineRunResult {
  Trajectory camera_states;  // T_W_I of every optimized stereo-frame state (IMU clock)
  Trajectory imu_poses;      // T_W_I propagated at every IMU sample after initialization
  std::vector<int> matches_per_frame;
  std::vector<double> frontend_ms;  // per stereo frame
  std::vector<double> smoother_ms;  // per stereo frame (Vio::add_frame)
  std::size_t imu_samples = 0;
};

// Runs the whole sequence. Throws InputError for bad input, including a dataset without cameras and
// IMU (KITTI odometry).
OfflineRunResult run_offline(DatasetReader& reader, const OfflineRunConfig& config);

}  // namespace vilslam
