#include "io/dataset_groundtruth.h"

#include <filesystem>

#include "common/error.h"
#include "io/dataset.h"
#include "io/groundtruth_mounts.h"
#include "io/trajectory_io.h"

namespace vilslam {

Trajectory dataset_groundtruth(const std::string& dataset_path, GroundTruthFrame frame) {
  const auto reader = open_dataset(dataset_path);
  const RigCalibration& calib = reader->calibration();
  if (frame == GroundTruthFrame::kLidar && !calib.has_lidar) {
    throw InputError(dataset_path, "dataset has no LiDAR calibration for a LiDAR-frame ground truth");
  }
  // The LiDAR's true mount where the dataset has one (a simulation with sensor realism), else the calibration's.
  SE3 T_I_B;
  if (frame == GroundTruthFrame::kLidar) {
    const std::optional<GroundTruthMounts> mounts = read_groundtruth_mounts(dataset_path);
    T_I_B = mounts ? mounts->T_I_L : calib.T_I_L;
  }
  Trajectory gt;
  for (const GroundTruthState& g : reader->groundtruth()) gt.push_back({g.t_ns, g.T_W_I * T_I_B});
  if (gt.empty()) throw InputError(dataset_path, "dataset has no ground truth");
  return gt;
}

Trajectory read_groundtruth(const std::string& path, GroundTruthFrame frame) {
  if (std::filesystem::is_directory(path)) return dataset_groundtruth(path, frame);
  return read_trajectory(path, TrajectoryFormat::kTum);
}

}  // namespace vilslam
