#include "pipeline/lidar_feeder.h"

#include <algorithm>

namespace vilslam {

LidarFeeder::LidarFeeder(const lidar::LidarMapperConfig& config, const RigCalibration& calib,
                         const Trajectory* imu_poses, std::vector<lidar::LidarMappingResult>* results)
    : mapper_(config, calib.T_I_L), offset_ns_(calib.lidar_time_offset_ns), imu_poses_(imu_poses), results_(results) {}

void LidarFeeder::scan(LidarScan scan) {
  scan.t_ns += offset_ns_;
  if (!imu_poses_) {
    results_->push_back(mapper_.process(scan, {}));
    return;
  }
  waiting_.push_back(std::move(scan));
  poses_advanced();
}

void LidarFeeder::poses_advanced() {
  while (!waiting_.empty() && !imu_poses_->empty() && imu_poses_->back().t_ns >= waiting_.front().end_t_ns()) {
    const LidarScan& scan = waiting_.front();
    if (scan.t_ns < imu_poses_->front().t_ns) {
      ++unmapped_;  // the VIO was not initialized yet at the sweep's start
    } else {
      results_->push_back(mapper_.process(scan, [this](TimeNs t_ns) { return interpolated_T_W_I(t_ns); }));
    }
    waiting_.pop_front();
  }
}

SE3 LidarFeeder::interpolated_T_W_I(TimeNs t_ns) const {
  const Trajectory& poses = *imu_poses_;
  const auto after = std::lower_bound(poses.begin(), poses.end(), t_ns,
                                      [](const TimedPose& p, TimeNs t) { return p.t_ns < t; });
  if (after == poses.begin()) return poses.front().T_W_B;
  if (after == poses.end()) return poses.back().T_W_B;
  const TimedPose& before = *(after - 1);
  const double alpha = static_cast<double>(t_ns - before.t_ns) / static_cast<double>(after->t_ns - before.t_ns);
  return interpolate(before.T_W_B, after->T_W_B, alpha);
}

}  // namespace vilslam
