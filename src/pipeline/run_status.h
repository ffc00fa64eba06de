#pragma once
// The modules' statuses of a run (issue: a status per frame and per sweep that says what happened):
// vio_status.csv and lidar_status.csv (docs/formats.md), and the stretches of each non-nominal status, which
// the run summary prints (a camera blackout shows as the VIO's inertial_only stretch, a LiDAR dropout as the
// sweep after_gap, an IMU gap as the VIO's imu_gap states).
#include <string>
#include <vector>

#include "pipeline/run_types.h"

namespace vilslam {

std::string vio_status_csv(const std::vector<VioStatusRecord>& states);
// The mapped and the rejected sweeps (OfflineRunResult::lidar, lidar_rejected), one row each in time order.
std::string lidar_status_csv(const std::vector<lidar::LidarMappingResult>& sweeps,
                             const std::vector<lidar::LidarMappingResult>& rejected);

struct StatusStretch {
  std::string module;  // "vio" | "lidar"
  std::string status;  // vio_status_name / mapping_status_name
  TimeNs begin_t_ns = 0, end_t_ns = 0;  // first and last record's time
  std::size_t count = 0;
  double gap_s = 0;  // lidar after_gap: the seconds without sweeps before it; vio imu_gap: summed
};

// Consecutive records of one status other than tracking / ok (degenerate sweeps too: the run counts them
// apart), rejected sweeps included, joined while less than join_s apart, in time order per module (VIO first).
std::vector<StatusStretch> status_stretches(const OfflineRunResult& run, double join_s = 1.0);

}  // namespace vilslam
