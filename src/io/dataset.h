#pragma once
// A dataset is read as one time-ordered stream of sensor events. Readers index the sequence up front
// (CSV rows, file names) and load images and scans only when their event is returned, so a sequence
// is never held in memory as a whole.
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "common/calibration.h"
#include "common/types.h"

namespace vilslam {

struct SensorEvent {
  TimeNs t_ns = 0;
  std::variant<ImuSample, StereoFrame, LidarScan, GroundTruthState> data;
};

// What `vilslam info` reports about a dataset, computed from its index without loading payloads.
struct DatasetSummary {
  std::string format;  // "euroc", "vilslam", "kitti"
  std::string path;
  std::size_t stereo_frames = 0;
  std::size_t imu_samples = 0;
  std::size_t lidar_scans = 0;
  std::size_t groundtruth_poses = 0;
  TimeNs start_t_ns = 0;
  TimeNs end_t_ns = 0;
  double camera_rate_hz = 0;
  double imu_rate_hz = 0;
  double lidar_rate_hz = 0;
  std::vector<std::string> problems;  // skipped rows, gaps larger than 1.5 periods, missing files
  std::string calibration = "layout";  // "layout", "kalibr" when Kalibr files beside the data replaced it, or
                                       // "file PATH" when DatasetOptions::calibration_path did
  std::vector<std::string> topics;    // ROS bags: "role topic type [layout]" of each stream read
};

// How to open a dataset: the calibration for any layout, the topics of a ROS1 bag file (docs/formats.md,
// "ROS1 bags"; folders ignore them).
struct DatasetOptions {
  std::string calibration_path;  // rig YAML replacing the dataset's; a bag's default: <bag without .bag>.rig.yaml
  std::map<std::string, std::string> topics;  // role (cam0, cam1, imu0, lidar0, groundtruth) -> topic
};

class DatasetReader {
 public:
  virtual ~DatasetReader() = default;
  // Next event in time order (ties: IMU, ground truth, stereo, LiDAR); nullopt at the end.
  // Throws InputError (naming the file) when a payload turns out to be corrupt.
  virtual std::optional<SensorEvent> next() = 0;
  virtual void rewind() = 0;
  virtual const RigCalibration& calibration() const = 0;
  virtual const DatasetSummary& summary() const = 0;
  // Ground truth of the whole sequence (small; may be empty).
  virtual const std::vector<GroundTruthState>& groundtruth() const = 0;
  // Path of the reference model cloud, empty when the dataset has none.
  virtual std::string reference_model_path() const { return {}; }
};

// Detects the layout (EuRoC ASL, the project's folder format, KITTI odometry, a ROS1 bag file) and opens it.
// Throws InputError naming the path when it is missing or not a known layout.
std::unique_ptr<DatasetReader> open_dataset(const std::string& path, const DatasetOptions& options = {});

}  // namespace vilslam
