#include "vio/loss_check.h"

#include <algorithm>

namespace vilslam {

std::string vio_loss_name(VioLoss loss) {
  switch (loss) {
    case VioLoss::kNone: return "none";
    case VioLoss::kNotFinite: return "lost_not_finite";
    case VioLoss::kSpeed: return "lost_speed";
    case VioLoss::kBias: return "lost_bias";
    case VioLoss::kInconsistent: return "lost_inconsistent";
  }
  return "unknown";
}

VioLoss VioLossCheck::check(const NavState& x, const Mat15& covariance, int frame_matches, int landmarks,
                            double final_cost) {
  if (!config_.enabled) return VioLoss::kNone;
  if (!x.R_W_I.allFinite() || !x.p_W_I.allFinite() || !x.v_W_m_s.allFinite() || !x.bias_gyro_rad_s.allFinite() ||
      !x.bias_accel_m_s2.allFinite() || !covariance.allFinite()) {
    return VioLoss::kNotFinite;
  }
  if (x.v_W_m_s.norm() > config_.max_speed_m_s) return VioLoss::kSpeed;
  if (x.bias_gyro_rad_s.norm() > config_.max_gyro_bias_rad_s || x.bias_accel_m_s2.norm() > config_.max_accel_bias_m_s2) {
    return VioLoss::kBias;
  }
  // A frame with too few matches (a bare wall, a blackout) says nothing either way: it counts as consistent.
  const bool inconsistent = frame_matches >= config_.min_frame_matches &&
                            (landmarks < config_.min_landmark_share * frame_matches ||
                             final_cost > config_.max_cost_per_landmark * cost_scale_ * std::max(landmarks, 1));
  recent_.push_back(inconsistent);
  if (static_cast<int>(recent_.size()) > config_.recent_states) recent_.pop_front();
  const int count = static_cast<int>(std::count(recent_.begin(), recent_.end(), true));
  return count >= config_.inconsistent_states ? VioLoss::kInconsistent : VioLoss::kNone;
}

}  // namespace vilslam
