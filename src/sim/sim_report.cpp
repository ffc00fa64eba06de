#include "sim/sim_report.h"

#include <opencv2/imgproc.hpp>

#include <cstdio>

#include "common/json_writer.h"

namespace vilslam::sim {

int count_corners(const cv::Mat& grey) {
  std::vector<cv::Point2f> corners;
  cv::goodFeaturesToTrack(grey, corners, /*maxCorners=*/1000, /*qualityLevel=*/0.01, /*minDistance=*/10.0);
  return static_cast<int>(corners.size());
}

double path_length_m(const std::vector<GroundTruthState>& states) {
  double length = 0;
  for (std::size_t k = 1; k < states.size(); ++k)
    length += (states[k].T_W_I.translation() - states[k - 1].T_W_I.translation()).norm();
  return length;
}

std::string report_table(const std::vector<SequenceReport>& reports) {
  std::string out = "scenario    length_m  duration_s  imu     frames  scans  gt      corners/frame  lidar_info_ratio\n";
  char row[256];
  for (const SequenceReport& r : reports) {
    std::snprintf(row, sizeof row, "%-10s  %8.1f  %10.1f  %-6zu  %-6zu  %-5zu  %-6zu  %13.1f  %16.4f\n", r.scenario.c_str(),
                  r.length_m, r.duration_s, r.imu_samples, r.stereo_frames, r.lidar_scans, r.groundtruth_states,
                  r.mean_corners_per_frame, r.mean_lidar_information_ratio);
    out += row;
  }
  return out;
}

void write_report_json(const std::string& path, const std::vector<SequenceReport>& reports) {
  JsonWriter json;
  json.begin_object().key("sequences").begin_array();
  for (const SequenceReport& r : reports) {
    json.begin_object();
    json.key("scenario").value(r.scenario);
    json.key("length_m").value(r.length_m);
    json.key("duration_s").value(r.duration_s);
    json.key("imu_samples").value(static_cast<std::uint64_t>(r.imu_samples));
    json.key("stereo_frames").value(static_cast<std::uint64_t>(r.stereo_frames));
    json.key("lidar_scans").value(static_cast<std::uint64_t>(r.lidar_scans));
    json.key("groundtruth_states").value(static_cast<std::uint64_t>(r.groundtruth_states));
    json.key("mean_corners_per_frame").value(r.mean_corners_per_frame);
    json.key("mean_lidar_information_ratio").value(r.mean_lidar_information_ratio);
    json.end_object();
  }
  json.end_array().end_object();
  json.save(path);
}

}  // namespace vilslam::sim
