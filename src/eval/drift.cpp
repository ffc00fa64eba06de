#include "eval/drift.h"

#include <stdexcept>

namespace vilslam::eval {
namespace {

FinalDrift relative(double drift_m, double length_m) {
  return {drift_m, length_m, length_m > 0 ? 100.0 * drift_m / length_m : 0.0};
}

}  // namespace

double path_length_m(const Trajectory& traj) {
  double length = 0;
  for (std::size_t i = 1; i < traj.size(); ++i) {
    length += (traj[i].T_W_B.translation() - traj[i - 1].T_W_B.translation()).norm();
  }
  return length;
}

FinalDrift final_drift(const Trajectory& est) {
  if (est.empty()) return {};
  return relative((est.back().T_W_B.translation() - est.front().T_W_B.translation()).norm(), path_length_m(est));
}

FinalDrift final_drift_start_aligned(const Trajectory& gt, const Trajectory& est) {
  if (gt.size() != est.size() || gt.empty()) throw std::invalid_argument("final drift needs matched trajectories");
  const SE3 T_gt_est = gt.front().T_W_B * est.front().T_W_B.inverse();
  const Vec3 p_last = T_gt_est * est.back().T_W_B.translation();
  return relative((p_last - gt.back().T_W_B.translation()).norm(), path_length_m(gt));
}

}  // namespace vilslam::eval
