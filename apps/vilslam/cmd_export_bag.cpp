// `vilslam export-bag DATASET --out FILE.bag [--no-groundtruth] [--out-topic ROLE=TOPIC] [--overwrite]`:
// any dataset vilslam reads as a ROS1 bag, with its calibration beside it (docs/formats.md, "ROS1 bags").
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "io/rosbag_export.h"
#include "vilslam/command.h"
#include "vilslam/dataset_options.h"

namespace {

using namespace vilslam;

struct Options {
  std::string dataset;
  std::string out;
  bool no_groundtruth = false;
  bool overwrite = false;
  std::vector<std::string> out_topics;
};

vilslam::cli::Command reg("export-bag", "Write a dataset as a ROS1 bag (Image, Imu, PointCloud2, PoseStamped)",
                          [](CLI::App& app) {
  auto o = std::make_shared<Options>();
  app.add_option("dataset", o->dataset, "Dataset folder or ROS1 .bag file")->required();
  const auto in_args = vilslam::cli::add_dataset_options(app);
  app.add_option("--out", o->out, "Bag to write (FILE.bag; the calibration goes to FILE.rig.yaml)")->required();
  app.add_option("--out-topic", o->out_topics,
                 "ROLE=TOPIC for the written bag (defaults /cam0/image_raw, /cam1/image_raw, /imu0, /lidar0/points, "
                 "/groundtruth/pose)");
  app.add_flag("--no-groundtruth", o->no_groundtruth, "Leave the ground truth out");
  app.add_flag("--overwrite", o->overwrite, "Replace an existing bag");
  return [o, in_args]() {
    BagExportOptions options;
    options.groundtruth = !o->no_groundtruth;
    options.overwrite = o->overwrite;
    for (const auto& [role, topic] : vilslam::cli::parse_topic_args(o->out_topics)) {
      if (!options.topics.count(role)) {
        throw std::invalid_argument("--out-topic: unknown role '" + role + "' (cam0, cam1, imu0, lidar0, groundtruth)");
      }
      options.topics[role] = topic;
    }
    const auto reader = open_dataset(o->dataset, vilslam::cli::dataset_options(*in_args));
    const BagExportCounts n = export_bag(*reader, o->out, options);
    std::printf("wrote %s: %zu stereo frames, %zu IMU samples, %zu LiDAR sweeps, %zu ground-truth poses\n",
                o->out.c_str(), n.stereo_frames, n.imu_samples, n.lidar_scans, n.groundtruth_poses);
    std::printf("wrote %s\n", bag_calibration_path(o->out).c_str());
    return 0;
  };
});

}  // namespace
