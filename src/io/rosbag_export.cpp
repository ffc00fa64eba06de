// export_bag: events of a dataset reader as ROS1 messages.
#include "io/rosbag_export.h"

#include <filesystem>

#include "common/error.h"
#include "io/calibration_io.h"
#include "io/ros_convert.h"
#include "io/rosbag_file.h"

namespace vilslam {

std::string bag_calibration_path(const std::string& bag_path) {
  return std::filesystem::path(bag_path).replace_extension(".rig.yaml").string();
}

BagExportCounts export_bag(DatasetReader& reader, const std::string& bag_path, const BagExportOptions& options) {
  namespace fs = std::filesystem;
  if (fs::path(bag_path).extension() != ".bag") throw std::invalid_argument(bag_path + ": the bag's name must end in .bag");
  if (fs::exists(bag_path) && !options.overwrite) {
    throw InputError(bag_path, "exists (use --overwrite to replace it)");
  }
  const auto& topic = options.topics;
  BagOut bag(bag_path);
  BagExportCounts counts;
  reader.rewind();
  while (const auto event = reader.next()) {
    if (const auto* imu = std::get_if<ImuSample>(&event->data)) {
      bag.write(topic.at("imu0"), kRosImu, imu->t_ns, encode(ros_imu_from_sample(*imu)));
      ++counts.imu_samples;
    } else if (const auto* frame = std::get_if<StereoFrame>(&event->data)) {
      bag.write(topic.at("cam0"), kRosImage, frame->t_ns, encode(ros_image_from_grey(frame->left, frame->t_ns, "cam0")));
      bag.write(topic.at("cam1"), kRosImage, frame->t_ns, encode(ros_image_from_grey(frame->right, frame->t_ns, "cam1")));
      ++counts.stereo_frames;
    } else if (const auto* scan = std::get_if<LidarScan>(&event->data)) {
      bag.write(topic.at("lidar0"), kRosPointCloud2, scan->t_ns, encode(velodyne_point_cloud2(*scan, "lidar0")));
      ++counts.lidar_scans;
    } else if (const auto* gt = std::get_if<GroundTruthState>(&event->data); gt && options.groundtruth) {
      bag.write(topic.at("groundtruth"), kRosPoseStamped, gt->t_ns, encode(ros_pose_from_state(*gt)));
      ++counts.groundtruth_poses;
    }
  }
  write_rig_yaml(bag_calibration_path(bag_path), reader.calibration());
  bag.finish();
  return counts;
}

}  // namespace vilslam
