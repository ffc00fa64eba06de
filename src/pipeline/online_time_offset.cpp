#include "pipeline/online_time_offset.h"

#include <vector>

namespace vilslam {

OnlineTimeOffsetEstimator::OnlineTimeOffsetEstimator(const TimeOffsetConfig& config, const Mat3& R_I_C0)
    : config_(config), R_I_C0_(R_I_C0) {}

void OnlineTimeOffsetEstimator::add_imu(const ImuSample& sample) {
  imu_.push_back(sample);
  // Samples older than any interval the window can hold, shifted by the largest offset, are not needed (one more
  // is kept before them), whether or not rotations arrive.
  const TimeNs keep_from_ns = sample.t_ns - s_to_ns(config_.online_window_s + 2 * config_.max_abs_offset_s);
  while (imu_.size() > 1 && imu_[1].t_ns < keep_from_ns) imu_.pop_front();
}

std::optional<TimeOffsetEstimate> OnlineTimeOffsetEstimator::add_rotation(const CameraRotation& rotation) {
  rotations_.push_back(rotation);
  const TimeNs now_ns = rotation.t_b_ns;
  while (rotations_.size() > 1 && rotations_.front().t_a_ns < now_ns - s_to_ns(config_.online_window_s)) {
    rotations_.pop_front();
  }
  if (!last_try_ns_) last_try_ns_ = now_ns;
  if (now_ns - *last_try_ns_ < s_to_ns(config_.update_every_s)) return std::nullopt;
  last_try_ns_ = now_ns;
  return estimate_cam_time_offset(std::vector<CameraRotation>(rotations_.begin(), rotations_.end()),
                                  std::vector<ImuSample>(imu_.begin(), imu_.end()), R_I_C0_, config_);
}

}  // namespace vilslam
