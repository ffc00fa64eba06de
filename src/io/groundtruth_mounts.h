#pragma once
// The sensors' true mounts of a dataset simulated with sensor realism (docs/formats.md, "Ground-truth sensor
// mounts"): ground truth like the trajectory, for evaluation only. The calibration the estimator reads (rig.yaml)
// is the nominal one; nothing on the estimator's side reads this file. The LiDAR's ground-truth poses go through
// its true mount (io/dataset_groundtruth.h): through the nominal one, a relative pose between two LiDAR poses
// d metres apart is off by about d times the mount's rotation error (0.5 deg: 0.9 cm per metre).
#include <optional>
#include <string>

#include "common/lie.h"

namespace vilslam {

struct GroundTruthMounts {
  SE3 T_I_C0, T_I_C1, T_I_L;
};

// Inside the dataset folder, beside the ground-truth trajectory.
constexpr const char* kGroundTruthMountsFile = "mav0/state_groundtruth_estimate0/sensor_mounts.yaml";

std::string groundtruth_mounts_yaml(const GroundTruthMounts& mounts);
// nullopt when the dataset has no such file (real data, ideal simulations, simulations before 2026-11-27); an
// InputError naming the file when it is there but unreadable.
std::optional<GroundTruthMounts> read_groundtruth_mounts(const std::string& dataset_path);

}  // namespace vilslam
