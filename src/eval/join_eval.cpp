#include "eval/join_eval.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "common/lie.h"
#include "eval/alignment.h"
#include "eval/association.h"

namespace vilslam::eval {
namespace {

// The poses with t in [from_ns, to_ns).
Trajectory between(const Trajectory& traj, TimeNs from_ns, TimeNs to_ns) {
  Trajectory out;
  for (const TimedPose& p : traj) {
    if (p.t_ns >= from_ns && p.t_ns < to_ns) out.push_back(p);
  }
  return out;
}

}  // namespace

JoinError join_error(const Trajectory& est_T_W_L, const Trajectory& gt_T_W_L, TimeNs reset_t_ns, TimeNs joined_t_ns,
                     TimeNs end_t_ns, double window_s) {
  const TimeNs window_ns = s_to_ns(window_s);
  const Trajectory before = between(est_T_W_L, reset_t_ns - window_ns, reset_t_ns);
  const Association fit = associate(before, gt_T_W_L);
  if (fit.size() < 3) throw std::invalid_argument("join_error: fewer than 3 poses with ground truth before the reset");
  const Alignment a = align_trajectories(select(before, fit.est_ids), select(gt_T_W_L, fit.gt_ids), AlignMode::kSe3);
  const Trajectory after = apply_alignment(between(est_T_W_L, joined_t_ns, std::min(end_t_ns, joined_t_ns + window_ns)), a);
  const Association compared = associate(after, gt_T_W_L);
  if (compared.size() == 0) throw std::invalid_argument("join_error: no pose with ground truth after the join");
  JoinError e;
  const TimedPose& last_before = before[fit.est_ids.back()];
  const TimedPose& first_joined = after[compared.est_ids.front()];  // aligned, but the relative pose is unchanged
  const SE3 est_rel = last_before.T_W_B.inverse() * a.T_gt_est.inverse() * first_joined.T_W_B;
  const SE3 gt_rel = gt_T_W_L[fit.gt_ids.back()].T_W_B.inverse() * gt_T_W_L[compared.gt_ids.front()].T_W_B;
  const SE3 junction = gt_rel.inverse() * est_rel;
  e.junction_translation_m = junction.translation().norm();
  e.junction_rotation_deg = so3::log(junction.rotation()).norm() * 180.0 / M_PI;
  e.fitted_poses = fit.size();
  e.joined_poses = compared.size();
  double sum_sq = 0;
  for (std::size_t i = 0; i < compared.size(); ++i) {
    const double dt =
        (after[compared.est_ids[i]].T_W_B.translation() - gt_T_W_L[compared.gt_ids[i]].T_W_B.translation()).norm();
    sum_sq += dt * dt;
    e.max_translation_m = std::max(e.max_translation_m, dt);
  }
  e.rmse_translation_m = std::sqrt(sum_sq / compared.size());
  return e;
}

}  // namespace vilslam::eval
