#pragma once
// Telling when the VIO has lost track (issue: "the system notices when a module has lost track"), from what one
// solve leaves: a state that is not finite, a speed or a bias no rig of this kind reaches, or a window that keeps
// disagreeing with the images while the frontend still tracks plenty of matches: the IMU factors pulled it off the
// motion, so the chi-square test dropped most landmarks or the solve's cost per landmark stays far above a
// consistent window's (the divergence an IMU fault starts; docs/vio.md "Losing track").
#include <deque>
#include <string>

#include "common/types.h"
#include "vio/window_state.h"

namespace vilslam {

struct VioLossConfig {
  bool enabled = true;                 // false: never declared lost (the window keeps whatever it converges to)
  double max_speed_m_s = 30.0;         // faster than any robot this rig rides on
  double max_gyro_bias_rad_s = 0.3;    // MEMS gyro biases stay under ~0.05 rad/s
  double max_accel_bias_m_s2 = 2.0;    // MEMS accelerometer biases stay under ~0.5 m/s^2
  int min_frame_matches = 15;          // a frame with fewer matches says nothing about vision being rejected
  double min_landmark_share = 0.1;     // landmarks in the solve / the frame's matches below this: inconsistent
  double max_cost_per_landmark = 15.0; // the solve's final cost / its landmarks above this: inconsistent (10 states)
  int recent_states = 10;              // of the last recent_states states,
  int inconsistent_states = 6;         // that many inconsistent: lost
};

enum class VioLoss { kNone, kNotFinite, kSpeed, kBias, kInconsistent };

// The status name of a loss ("lost_not_finite", ...; docs/formats.md).
std::string vio_loss_name(VioLoss loss);

// Keeps which of the recent states were inconsistent; check() is called once per solved state.
class VioLossCheck {
 public:
  // The window max_cost_per_landmark is set for (the smoother's default, SmootherConfig::window_size).
  static constexpr int kReferenceWindowStates = 10;

  // window_states: the smoother's window. A consistent landmark's cost grows with its observations, up to one per
  // state, so max_cost_per_landmark scales by window_states / kReferenceWindowStates.
  explicit VioLossCheck(const VioLossConfig& config, int window_states = kReferenceWindowStates)
      : config_(config), cost_scale_(static_cast<double>(window_states) / kReferenceWindowStates) {}

  // final_cost: the window's cost after the solve (SmootherStats), landmarks: those with a vision factor in it.
  VioLoss check(const NavState& x, const Mat15& covariance, int frame_matches, int landmarks, double final_cost);
  void reset() { recent_.clear(); }

 private:
  VioLossConfig config_;
  double cost_scale_;
  std::deque<bool> recent_;  // inconsistent or not, the newest last
};

}  // namespace vilslam
