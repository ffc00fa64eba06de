#pragma once
// The camera-IMU time offset estimated as the run goes (`time_offset.online`; beyond the paper, which assumes
// synchronized sensors; VINS-Fusion and OpenVINS estimate it online too, inside their estimators). The frontend's
// frame-to-frame rotations of the last online_window_s and the IMU samples over them are matched by the estimator of
// vio/time_offset.h every update_every_s of camera time, the same estimator as the pass before the run
// (pipeline/time_offset_pass.h) on the data seen so far. Each estimate moves the frames that follow onto the
// IMU clock (the frontend side of pipeline/system.cpp).
#include <deque>
#include <optional>

#include "common/types.h"
#include "vio/time_offset.h"

namespace vilslam {

class OnlineTimeOffsetEstimator {
 public:
  OnlineTimeOffsetEstimator(const TimeOffsetConfig& config, const Mat3& R_I_C0);

  // Samples in time order (IMU clock).
  void add_imu(const ImuSample& sample);
  // The left camera's rotation over an interval of camera time, intervals in time order. Returns an estimate when
  // one is due (update_every_s since the last try) and the window makes the offset observable.
  std::optional<TimeOffsetEstimate> add_rotation(const CameraRotation& rotation);

 private:
  TimeOffsetConfig config_;
  Mat3 R_I_C0_;
  std::deque<ImuSample> imu_;
  std::deque<CameraRotation> rotations_;
  std::optional<TimeNs> last_try_ns_;
};

}  // namespace vilslam
