#pragma once
// Camera-IMU time offset from rotation alone (beyond the paper; VINS-Mono and Kalibr estimate it too): the
// left camera's frame-to-frame rotations, measured visually, against the gyro integrated over the same
// intervals shifted by a candidate offset. With t_imu = t_cam + offset (common/calibration.h) and the
// camera-IMU rotation R_I_C0 known, each interval k gives
//   u_k(offset) = int_{t_a + offset}^{t_b + offset} omega dt - R_I_C0 log(R_C0a_C0b)   (I frame, rad)
// whose mean part is the gyro bias times the interval: b = sum(dt_k u_k) / sum(dt_k^2). The offset
// minimizes sum ||u_k - b dt_k||^2: a grid search, then a parabola through the best grid point and its
// neighbours.
#include <optional>
#include <vector>

#include "common/lie.h"
#include "common/types.h"

namespace vilslam {

struct TimeOffsetConfig {
  bool enabled = false;          // estimate before the run and use it instead of the calibration's
  bool online = false;           // estimate again as the run goes (pipeline/online_time_offset.h)
  double update_every_s = 5.0;   // online: seconds of camera time between estimates
  double online_window_s = 120.0;  // online: the camera intervals of the last online_window_s are used
  double window_s = 30.0;        // before the run: camera intervals from the sequence's first window_s are used
  double max_abs_offset_s = 0.05;  // searched over [-max, max]
  double grid_step_s = 0.0005;
  double min_rotation_rad_s = 0.1;  // rotation rate the window must reach (else the offset is unobservable)
  int min_intervals = 50;
};

// The visually measured rotation of the left camera over [t_a_ns, t_b_ns] (camera clock).
struct CameraRotation {
  TimeNs t_a_ns = 0, t_b_ns = 0;
  Mat3 R_C0a_C0b = Mat3::Identity();
};

struct TimeOffsetEstimate {
  double offset_s = 0;            // t_imu = t_cam + offset
  Vec3 gyro_bias_rad_s = Vec3::Zero();
  double rms_rad = 0;             // residual rms per interval at the optimum
  double rms_zero_offset_rad = 0; // the same with offset 0 (how much the offset explains)
  int intervals = 0;
};

// nullopt when fewer than config.min_intervals intervals lie inside the IMU stream for every candidate
// offset, or when the camera never turned faster than config.min_rotation_rad_s. imu: time-sorted.
std::optional<TimeOffsetEstimate> estimate_cam_time_offset(const std::vector<CameraRotation>& rotations,
                                                           const std::vector<ImuSample>& imu, const Mat3& R_I_C0,
                                                           const TimeOffsetConfig& config);

}  // namespace vilslam
