// Layout detection: a ROS1 bag (a .bag file), a ROS 2 bag (a folder with metadata.yaml, or a .db3 or .mcap
// file), the project's format (rig.yaml or mav0/lidar0), EuRoC ASL (mav0/), KITTI odometry; then, for folders,
// Kalibr calibration files in the folder when there are any, and last a rig YAML the caller names (`--calib`),
// which replaces them all, or a Kalibr camchain it names, which replaces what its files hold.
#include <filesystem>

#include "common/error.h"
#include "io/calibration_io.h"
#include "io/dataset_index.h"
#include "io/kalibr_calibration.h"
#include "io/message_log.h"

namespace vilslam {

DatasetIndex index_dataset(const std::string& root, const DatasetOptions& options) {
  namespace fs = std::filesystem;
  const fs::path dir(root);
  if (!fs::exists(dir)) throw InputError(root, "dataset folder does not exist");
  const bool bag = (fs::is_regular_file(dir) && dir.extension() == ".bag") || is_ros2_bag(root);
  if (!fs::is_directory(dir) && !bag) throw InputError(root, "not a folder, a ROS1 .bag file nor a ROS 2 .db3 or .mcap file");
  DatasetIndex index;
  if (bag) {
    index = index_rosbag(root, options);
  } else if (fs::exists(dir / "rig.yaml") || fs::exists(dir / "mav0" / "lidar0")) {
    index = index_vilslam(root);
  } else if (fs::is_directory(dir / "mav0")) {
    index = index_euroc(root);
  } else if (fs::exists(dir / "calib.txt") && fs::exists(dir / "times.txt")) {
    index = index_kitti(root);
  } else {
    throw InputError(root, "unknown dataset layout (expected mav0/, rig.yaml, or KITTI calib.txt and times.txt)");
  }
  // A user's Kalibr calibration next to the data replaces the layout's (docs/formats.md).
  if (!bag && apply_kalibr_folder(root, index.calibration)) index.summary.calibration = "kalibr";
  if (!bag && !options.calibration_path.empty()) {
    if (is_kalibr_camchain(options.calibration_path)) {  // on top of the layout's, as Kalibr files in the folder
      apply_kalibr_files(kalibr_files_beside(options.calibration_path), index.calibration);
      index.summary.calibration = "kalibr " + options.calibration_path;
    } else {
      index.calibration = read_rig_yaml(options.calibration_path);
      index.summary.calibration = "file " + options.calibration_path;
    }
  }
  finalize_summary(index);
  return index;
}

std::unique_ptr<DatasetReader> open_dataset(const std::string& path, const DatasetOptions& options) {
  return open_indexed(index_dataset(path, options));
}

}  // namespace vilslam
