#pragma once
// Any dataset as a ROS1 bag (docs/formats.md, "ROS1 bags"): stereo as mono8 sensor_msgs/Image, IMU as
// sensor_msgs/Imu, sweeps as PointCloud2 in the Velodyne driver's layout, ground truth (optional) as
// geometry_msgs/PoseStamped; the calibration beside it as <bag without .bag>.rig.yaml.
#include <cstddef>
#include <map>
#include <string>

#include "io/dataset.h"

namespace vilslam {

struct BagExportOptions {
  bool groundtruth = true;
  bool overwrite = false;
  // Topic of each role (cam0, cam1, imu0, lidar0, groundtruth); roles not given keep these defaults.
  std::map<std::string, std::string> topics = {{"cam0", "/cam0/image_raw"}, {"cam1", "/cam1/image_raw"},
                                               {"imu0", "/imu0"},           {"lidar0", "/lidar0/points"},
                                               {"groundtruth", "/groundtruth/pose"}};
};

struct BagExportCounts {
  std::size_t stereo_frames = 0, imu_samples = 0, lidar_scans = 0, groundtruth_poses = 0;
};

// Writes every event of the reader (from its start) into bag_path, atomically: <bag>.partial renamed at
// the end, the calibration written before the rename. An existing bag is an InputError unless overwrite.
BagExportCounts export_bag(DatasetReader& reader, const std::string& bag_path, const BagExportOptions& options);

// Where a bag's calibration lives by default: <bag without .bag>.rig.yaml.
std::string bag_calibration_path(const std::string& bag_path);

}  // namespace vilslam
