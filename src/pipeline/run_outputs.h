#pragma once
// Writes an offline run's results into an output folder: vio_camera.tum and vio_imu.tum (vio, vil),
// lidar.tum and degeneracy.csv (vil, lidar-only), timings.json.
// The folder is assembled as DIR.partial and renamed into place, so DIR is never half-written.
#include <string>

#include "pipeline/offline_runner.h"

namespace vilslam {

// Replaces out_dir when it exists. Throws std::runtime_error when a file cannot be written.
void write_run_outputs(const std::string& out_dir, RunMode mode, const OfflineRunResult& result);

}  // namespace vilslam
