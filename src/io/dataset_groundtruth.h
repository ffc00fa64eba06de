#pragma once
// A dataset's ground truth as a trajectory of the IMU body (T_W_I) or of the LiDAR (T_W_I T_I_L, with the
// LiDAR's true mount when the dataset has one, io/groundtruth_mounts.h, else the rig's extrinsic), for comparing
// LiDAR poses (`vilslam eval --gt DATASET --gt-frame lidar`, `eval-loops`, `eval-map`, `odometry-table`).
#include <string>

#include "common/types.h"

namespace vilslam {

enum class GroundTruthFrame { kImu, kLidar };

// Throws InputError naming the dataset when it has no ground truth, or no LiDAR calibration for kLidar.
Trajectory dataset_groundtruth(const std::string& dataset_path, GroundTruthFrame frame);

// A `--gt GT` argument: a dataset folder (its ground truth in `frame`) or a TUM file, whose poses are taken
// to be of that frame already. Throws InputError naming the path on any problem.
Trajectory read_groundtruth(const std::string& path, GroundTruthFrame frame);

}  // namespace vilslam
