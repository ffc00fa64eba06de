#pragma once
// The rotation of the LiDAR's mount from how the rig turned (hand-eye calibration, rotation part).
// Over a window [a, b] the IMU turns by A (its gyroscope integrated, less a bias estimated with the mount) and
// the LiDAR by B = R_W_L(a)^T R_W_L(b) (its odometry); one rigid mount R_I_L gives B = R_I_L^T A R_I_L. Turns
// about an axis tell the mount's rotation about the two axes across it: a ground robot turning about the
// vertical shows the mount's tilt, not its yaw, which stays at the nominal value. The noise of one window is
// taken from the fit's own residuals (a-posteriori variance). Used by `vilslam calibrate-lidar`
// (docs/calibration.md).
#include <vector>

#include "common/lie.h"
#include "common/types.h"

namespace vilslam::calib {

struct MountRotationConfig {
  double window_s = 2.0;            // each relative rotation spans this long
  double stride_s = 1.0;            // windows start this far apart
  double min_rotation_rad = 0.35;   // windows turning this much (20 deg) are counted as turns
  double huber_scales = 2.0;        // residuals beyond this many robust scales (1.4826 x median) count linearly
  double max_sigma_rad = 0.0035;    // a direction known worse than this (0.2 deg) keeps the nominal value
  int iterations = 10;              // Gauss-Newton with Huber weights
};

struct MountRotationEstimate {
  Mat3 R_I_L = Mat3::Identity();
  Vec3 correction_rad = Vec3::Zero();   // R_I_L = R_I_L_nominal Exp(correction), in L
  Mat3 covariance_rad2 = Mat3::Zero();  // of the correction, over the estimated directions (zero elsewhere)
  int estimated_directions = 0;         // 0-3: the directions the turns showed well enough
  Vec3 kept_direction = Vec3::Zero();   // with 2: the unit axis left at the nominal (yaw for turns about it)
  Vec3 gyro_bias_rad_s = Vec3::Zero();  // estimated with the mount, in I
  int windows = 0;                      // windows used (each with IMU samples and LiDAR poses around it)
  int turning_windows = 0;              // of those, the ones that turned min_rotation_rad or more
  double rms_residual_rad = 0.0;        // after the fit, over the turning windows
};

// Needs time-sorted IMU samples and LiDAR poses on one clock; windows are taken where both cover [a, b]
// without gaps (poses interpolated, the gyroscope preintegrated as the VIO does). With no turning window
// the nominal mount comes back unchanged.
MountRotationEstimate estimate_mount_rotation(const std::vector<ImuSample>& imu, const Trajectory& T_W_L,
                                              const Mat3& R_I_L_nominal, const MountRotationConfig& config = {});

}  // namespace vilslam::calib
