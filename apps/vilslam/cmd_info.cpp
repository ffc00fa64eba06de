// `vilslam info DATASET [--json OUT] [--deep]`: layout, sensors, counts, rates, gaps and problems,
// after validating every payload (cheaply by default, by decoding with --deep).
#include <cstdio>
#include <iostream>
#include <memory>
#include <optional>

#include "common/json_writer.h"
#include "io/calibration_io.h"
#include "io/dataset_index.h"
#include "lidar/sensor_traits.h"
#include "vilslam/command.h"
#include "vilslam/dataset_options.h"

namespace {

using namespace vilslam;

struct Options {
  std::string dataset;
  std::string json_path;
  bool deep = false;
};

std::vector<std::string> sensors(const DatasetIndex& index) {
  std::vector<std::string> names;
  const RigCalibration& c = index.calibration;
  if (index.has_cameras) {
    for (const auto& [name, cam] : {std::pair{"cam0 ", &c.cam0}, std::pair{"cam1 ", &c.cam1}}) {
      names.push_back(name + std::to_string(cam->width_px) + "x" + std::to_string(cam->height_px) + " pinhole " +
                      distortion_model_name(cam->distortion));
    }
  }
  if (!index.imu.empty()) names.push_back("imu0");
  if (c.has_lidar) names.push_back("lidar0 " + std::to_string(c.lidar.num_rings) + " rings");
  if (!index.groundtruth.empty()) names.push_back("groundtruth");
  return names;
}

void print(const DatasetIndex& index, const std::vector<std::string>& sensor_names, double duration_s) {
  const DatasetSummary& s = index.summary;
  std::printf("format: %s\npath: %s\ncalibration: %s\nsensors:", s.format.c_str(), s.path.c_str(),
              s.calibration.c_str());
  for (const auto& name : sensor_names) std::printf(" [%s]", name.c_str());
  std::printf("\nstereo_frames: %zu\nimu_samples: %zu\nlidar_scans: %zu\ngroundtruth_poses: %zu\n", s.stereo_frames,
              s.imu_samples, s.lidar_scans, s.groundtruth_poses);
  std::printf("duration_s: %.3f\ncamera_rate_hz: %.3f\nimu_rate_hz: %.3f\nlidar_rate_hz: %.3f\n", duration_s,
              s.camera_rate_hz, s.imu_rate_hz, s.lidar_rate_hz);
  if (!s.topics.empty()) {
    std::printf("topics:\n");
    for (const auto& t : s.topics) std::printf("  - %s\n", t.c_str());
  }
  std::printf("problems: %zu\n", s.problems.size());
  for (const auto& p : s.problems) std::printf("  - %s\n", p.c_str());
}

void write_json(const std::string& path, const DatasetIndex& index, const std::vector<std::string>& sensor_names,
                double duration_s, const std::optional<lidar::SensorTraits>& traits) {
  const DatasetSummary& s = index.summary;
  JsonWriter json;
  json.begin_object();
  json.key("format").value(s.format);
  json.key("path").value(s.path);
  json.key("calibration").value(s.calibration);
  json.key("sensors").begin_array();
  for (const auto& name : sensor_names) json.value(name);
  json.end_array();
  json.key("stereo_frames").value(static_cast<std::uint64_t>(s.stereo_frames));
  json.key("imu_samples").value(static_cast<std::uint64_t>(s.imu_samples));
  json.key("lidar_scans").value(static_cast<std::uint64_t>(s.lidar_scans));
  json.key("groundtruth_poses").value(static_cast<std::uint64_t>(s.groundtruth_poses));
  json.key("duration_s").value(duration_s);
  json.key("camera_rate_hz").value(s.camera_rate_hz);
  json.key("imu_rate_hz").value(s.imu_rate_hz);
  json.key("lidar_rate_hz").value(s.lidar_rate_hz);
  if (!s.topics.empty()) {
    json.key("topics").begin_array();
    for (const auto& t : s.topics) json.value(t);
    json.end_array();
  }
  json.key("problems").begin_array();
  for (const auto& p : s.problems) json.value(p);
  json.end_array();
  if (traits) {  // the LiDAR as a run reads it (lidar/sensor_traits.h)
    json.key("lidar_traits").begin_object();
    json.key("points").value(static_cast<std::uint64_t>(traits->points));
    json.key("read").value(traits->read());
    json.key("ring_field").value(traits->ring_field);
    json.key("point_times").value(traits->point_times);
    json.key("rings").value(traits->rings);
    json.key("min_elevation_deg").value(traits->min_elevation_deg);
    json.key("max_elevation_deg").value(traits->max_elevation_deg);
    json.key("azimuth_coverage").value(traits->azimuth_coverage);
    json.key("range_p10_m").value(traits->range_p10_m);
    json.key("range_median_m").value(traits->range_median_m);
    json.key("range_p90_m").value(traits->range_p90_m);
    json.key("range_max_m").value(traits->range_max_m);
    json.end_object();
  }
  json.end_object();
  json.save(path);
}

vilslam::cli::Command reg("info", "Describe and validate a dataset (EuRoC ASL, vilslam, KITTI odometry, ROS1 bag)",
                          [](CLI::App& app) {
  auto opts = std::make_shared<Options>();
  app.add_option("dataset", opts->dataset, "Dataset folder or ROS1 .bag file")->required();
  const auto bag_args = vilslam::cli::add_dataset_options(app);
  app.add_option("--json", opts->json_path, "Also write the summary as JSON to this file");
  app.add_flag("--deep", opts->deep, "Decode every image and scan (default: check headers and sizes only)");
  return [opts, bag_args]() {
    const DatasetIndex index = index_dataset(opts->dataset, vilslam::cli::dataset_options(*bag_args));
    check_payloads(index, opts->deep);
    const std::vector<std::string> names = sensors(index);
    const double duration_s = ns_to_s(index.summary.end_t_ns - index.summary.start_t_ns);
    print(index, names, duration_s);
    std::optional<lidar::SensorTraits> traits;
    if (!index.scans.empty()) traits = lidar::first_sweep_traits(index);
    if (traits) std::printf("%s", lidar::sensor_traits_text(*traits).c_str());
    if (!opts->json_path.empty()) write_json(opts->json_path, index, names, duration_s, traits);
    return 0;
  };
});

}  // namespace
