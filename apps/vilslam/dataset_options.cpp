#include "vilslam/dataset_options.h"

#include <stdexcept>

namespace vilslam::cli {

std::shared_ptr<DatasetOptionArgs> add_dataset_options(CLI::App& app) {
  auto args = std::make_shared<DatasetOptionArgs>();
  app.add_option("--calib", args->calibration_path,
                 "Rig YAML replacing the dataset's calibration, or a Kalibr camchain (camchain-imucam[-NAME].yaml, "
                 "with imu[-NAME].yaml and lidar-imu[-NAME].yaml beside it) replacing what its files hold "
                 "(docs/formats.md; a ROS bag's default: its name with .rig.yaml instead of .bag)");
  app.add_option("--topic", args->topics,
                 "ROS bag only: ROLE=TOPIC, role cam0, cam1, imu0, lidar0 or groundtruth (default: found by type)")
      ->allow_extra_args(false);
  return args;
}

std::map<std::string, std::string> parse_topic_args(const std::vector<std::string>& args) {
  std::map<std::string, std::string> topics;
  for (const std::string& a : args) {
    const auto eq = a.find('=');
    if (eq == std::string::npos || eq == 0 || eq + 1 == a.size()) {
      throw std::invalid_argument("--topic " + a + ": expected ROLE=TOPIC, e.g. cam0=/left/image_raw");
    }
    topics[a.substr(0, eq)] = a.substr(eq + 1);
  }
  return topics;
}

DatasetOptions dataset_options(const DatasetOptionArgs& args) {
  DatasetOptions options;
  options.calibration_path = args.calibration_path;
  options.topics = parse_topic_args(args.topics);
  return options;
}

}  // namespace vilslam::cli
