#pragma once
// Writes an offline run's results into an output folder: vio_camera.tum, vio_imu.tum and vio_status.csv (vio,
// vil), lidar.tum, degeneracy.csv and lidar_status.csv (vil, lidar-only; pipeline/run_status.h), with loop closure (vil) lidar_global.tum,
// lidar_final.tum, loops.csv and loop_candidates.csv, timings.json and timing_samples.csv (the samples it
// summarizes), and config.yaml (the effective run config, pipeline/run_config.h: `vilslam run --config
// DIR/config.yaml` repeats the run).
// The folder is assembled as DIR.partial and renamed into place, so DIR is never half-written.
#include <string>

#include "pipeline/offline_runner.h"

namespace vilslam {

// Replaces out_dir when it exists. Throws std::runtime_error when a file cannot be written.
void write_run_outputs(const std::string& out_dir, const OfflineRunConfig& config, const OfflineRunResult& result);

}  // namespace vilslam
