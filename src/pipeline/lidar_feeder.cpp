#include "pipeline/lidar_feeder.h"

#include <algorithm>

#include "common/log.h"
#include "lidar/azimuth_times.h"
#include "lidar/sensor_adaptation.h"

namespace vilslam {

LidarFeeder::LidarFeeder(const lidar::LidarMapperConfig& config, const RigCalibration& calib,
                         const Trajectory* imu_poses, const Trajectory* imu_motion,
                         const std::vector<double>* imu_tilt_sigma_rad,
                         std::vector<lidar::LidarMappingResult>* results,
                         std::vector<lidar::LidarMappingResult>* rejected, LoopClosureModule* loop,
                         bool reanchor_when_lost)
    : config_(config), T_I_L_(calib.T_I_L), offset_ns_(calib.lidar_time_offset_ns), rate_hz_(calib.lidar.rate_hz),
      dewarp_(config.dewarp), imu_poses_(imu_poses), imu_motion_(imu_motion),
      imu_tilt_sigma_rad_(imu_tilt_sigma_rad), results_(results), rejected_(rejected), loop_(loop),
      lost_after_rejected_(config.loss.lost_after_rejected), reanchor_when_lost_(reanchor_when_lost) {}

void LidarFeeder::know_sensor(const LidarScan& scan) {
  if (traits_) return;
  traits_ = lidar::read_sensor_traits(scan);
  if (!traits_->read()) {
    spdlog::warn("the first LiDAR sweep has {} returns: too few to read the sensor from", traits_->points);
  }
  mapper_.emplace(lidar::adapt_to_sensor(config_, *traits_), T_I_L_, s_to_ns(1.0 / rate_hz_),
                  traits_->read() && traits_->spinning());
}

bool LidarFeeder::azimuth_clock_possible() const { return dewarp_ && traits_->read() && traits_->spinning(); }

TimeNs LidarFeeder::latest_end_t_ns(const LidarScan& scan) const {
  const bool may_take_azimuth_times = azimuth_clock_possible() && !lidar::has_point_times(scan);
  return may_take_azimuth_times ? scan.t_ns + s_to_ns(1.0 / rate_hz_) : scan.end_t_ns();
}

std::string LidarFeeder::sensor_report() const {
  if (!traits_) return {};
  const bool may_need = azimuth_clock_possible() && !traits_->point_times;
  return lidar::sensor_traits_text(*traits_) + "lidar_azimuth_times: " + (may_need ? mapper_->azimuth_times() : "no") +
         "\n";
}

void LidarFeeder::scan(LidarScan scan) {
  scan.t_ns += offset_ns_;
  know_sensor(scan);
  if (!imu_poses_) {
    map(scan, {}, {});
    return;
  }
  waiting_.push_back(std::move(scan));
  poses_advanced();
}

void LidarFeeder::vio_lost() { lost_after_ = imu_poses_->size(); }

void LidarFeeder::finish() {
  poses_advanced();
  if (!lost_after_) return;
  for (; !waiting_.empty(); waiting_.pop_front()) map(waiting_.front(), {}, {});  // the VIO never started again
}

void LidarFeeder::poses_advanced() {
  if (lost_after_ && imu_poses_->size() > *lost_after_) {
    restarted_t_ns_ = (*imu_poses_)[*lost_after_].t_ns;
    lost_after_.reset();
  }
  while (!lost_after_ && !waiting_.empty() && !imu_poses_->empty() &&
         imu_poses_->back().t_ns >= latest_end_t_ns(waiting_.front())) {
    const LidarScan& scan = waiting_.front();
    if (scan.t_ns < imu_poses_->front().t_ns) {
      ++unmapped_;  // the VIO was not initialized yet at the sweep's start
    } else if (restarted_t_ns_ && scan.t_ns < *restarted_t_ns_) {
      map(scan, {}, {});  // the sweep began while the VIO was lost
    } else {
      std::function<SE3(TimeNs)> T_O_I;
      if (imu_motion_) T_O_I = [this](TimeNs t_ns) { return pose_at(*imu_motion_, t_ns); };
      // The VIO's tilt standard deviation at the first IMU-rate pose from the sweep's end on.
      double tilt_sigma_rad = 0.0;
      if (imu_tilt_sigma_rad_) {
        const auto at_end = std::lower_bound(imu_poses_->begin(), imu_poses_->end(), latest_end_t_ns(scan),
                                             [](const TimedPose& p, TimeNs t) { return p.t_ns < t; });
        tilt_sigma_rad = (*imu_tilt_sigma_rad_)[static_cast<std::size_t>(at_end - imu_poses_->begin())];
      }
      map(scan, [this](TimeNs t_ns) { return pose_at(*imu_poses_, t_ns); }, T_O_I, tilt_sigma_rad);
    }
    waiting_.pop_front();
  }
}

void LidarFeeder::map(const LidarScan& scan, const std::function<SE3(TimeNs)>& T_W_I_prior,
                      const std::function<SE3(TimeNs)>& T_O_I_dewarp, double prior_tilt_sigma_rad) {
  if (mapper_lost_t_ns_) {
    ++unmapped_;
    return;
  }
  // A loop correction that arrived since the last sweep comes first (paper, "Re-localization").
  if (loop_) {
    if (const auto correction = loop_->take_correction()) {
      mapper_->relocalize(correction->T_W_L_last, correction->key_scans);
    }
  }
  lidar::LidarMappingResult result = mapper_->process(scan, T_W_I_prior, T_O_I_dewarp, prior_tilt_sigma_rad);
  if (result.loss != lidar::MappingLoss::kNone) {
    if (++rejected_in_a_row_ >= lost_after_rejected_ && reanchor_when_lost_) {
      spdlog::warn("LiDAR mapping re-anchored at t_ns={}: {} sweeps in a row did not fit the map; a fresh local map "
                   "starts at the next sweep's predicted pose", result.t_ns, rejected_in_a_row_);
      mapper_->reanchor();
      rejected_in_a_row_ = 0;
    } else if (rejected_in_a_row_ >= lost_after_rejected_) {
      mapper_lost_t_ns_ = result.t_ns;
    }
    rejected_->push_back(std::move(result));
    return;
  }
  rejected_in_a_row_ = 0;
  results_->push_back(std::move(result));
  if (loop_) loop_->scan_mapped(results_->back(), mapper_->last_features());
}

}  // namespace vilslam
