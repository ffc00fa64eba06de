#pragma once
// What `vilslam simulate --report` prints per sequence and writes to report.json.
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "common/types.h"

namespace vilslam::sim {

struct SequenceReport {
  std::string scenario;
  double length_m = 0;            // distance travelled by the IMU over the written sequence
  double duration_s = 0;
  std::size_t imu_samples = 0;
  std::size_t stereo_frames = 0;
  std::size_t lidar_scans = 0;
  std::size_t groundtruth_states = 0;
  double mean_corners_per_frame = 0;       // Shi-Tomasi corners in the left images
  double mean_lidar_information_ratio = 0; // min/max eigenvalue of each sweep's point-to-plane information
                                           // (analyze_scan_degeneracy at the sweep start), averaged
};

// Shi-Tomasi corners (cv::goodFeaturesToTrack) of an 8-bit grey image.
int count_corners(const cv::Mat& grey);

// Distance travelled along the poses.
double path_length_m(const std::vector<GroundTruthState>& states);

// The table printed for the reports, one row each.
std::string report_table(const std::vector<SequenceReport>& reports);
// Atomic write of the reports as JSON.
void write_report_json(const std::string& path, const std::vector<SequenceReport>& reports);

}  // namespace vilslam::sim
