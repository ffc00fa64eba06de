#pragma once
// VIO initialization while moving (a restart mid-run): the stereo pairs of a short window give the camera's
// metric positions (stereo triangulation, then frame-to-frame PnP), the gyroscope the rotations between them, and
// the accelerometer preintegrated between the same pairs must explain the motion: one linear least-squares problem
// gives the velocity at every pair and gravity in the first camera's frame (VINS-Mono's visual-inertial alignment,
// Qin et al. 2018, Sec. V-B, with the scale known from the stereo baseline), and gravity's direction gives roll
// and pitch. The accelerometer alone cannot: while the robot accelerates or turns, its mean is not gravity.
// The gyroscope bias is calibrated first, on the visual rotations (Sec. V-B1); the accelerometer bias starts at 0
// (the smoother's prior holds it): over the window its effect is far below the noise.
#include <optional>
#include <string>
#include <vector>

#include "common/calibration.h"
#include "common/types.h"
#include "frontend/stereo_match.h"
#include "vio/window_state.h"

namespace vilslam {

struct VisualInertialAlignmentConfig {
  int frames = 20;                      // stereo pairs in the window (1 s at 20 Hz)
  int min_pnp_inliers = 15;             // per consecutive pair
  double max_rotation_mismatch_rad = 0.05;  // visual (chained PnP) against gyroscope rotation, at every pair
  double max_gravity_error_m_s2 = 0.5;  // | |g| - gravity | of the unconstrained solution
};

struct VisualInertialAlignment {
  std::optional<NavState> state;  // at the window's first pair (yaw 0, position 0, the gyro bias); none when it failed
  std::string failure;            // why not, when it failed
};

// frames: the window, in time order (frames[0].t_ns on the IMU clock); imu: samples covering
// [frames.front().t_ns, frames.back().t_ns]; focal_px: cam0's focal length (the PnP threshold's scale).
VisualInertialAlignment align_visual_inertial(const std::vector<FrontendOutput>& frames,
                                              const std::vector<ImuSample>& imu, const RigCalibration& calib,
                                              double focal_px, double gravity_m_s2,
                                              const VisualInertialAlignmentConfig& config);

}  // namespace vilslam
