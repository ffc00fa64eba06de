#pragma once
// VIO initialization from a static IMU segment: roll and pitch from the averaged specific force, yaw 0,
// gyro bias from the averaged angular rate (0 when the segment is not static), accelerometer bias 0, velocity 0. The stereo baseline fixes
// the metric scale, so no visual scale alignment is needed.
#include <vector>

#include "common/types.h"
#include "vio/visual_inertial_alignment.h"
#include "vio/window_state.h"

namespace vilslam {

struct InitializerConfig {
  double averaging_window_s = 1.0;     // samples in [t - window, t] are averaged
  double max_accel_std_m_s2 = 0.25;    // above this the rig is not considered static
  double max_gyro_std_rad_s = 0.05;
  // The robot may be moving at the first frame (a restart mid-run): initialize by visual-inertial alignment over
  // the first alignment.frames stereo pairs instead (vio/visual_inertial_alignment.h).
  bool moving_start = false;
  VisualInertialAlignmentConfig alignment;
};

struct Initialization {
  NavState state;
  bool is_static = false;  // false: the averages were taken while moving (biases and attitude are rough)
  int samples = 0;
};

// Throws std::invalid_argument when no sample lies in the averaging window.
Initialization static_initialization(const std::vector<ImuSample>& samples, TimeNs t_ns,
                                     const InitializerConfig& config);

}  // namespace vilslam
