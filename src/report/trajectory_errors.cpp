#include "report/trajectory_errors.h"

#include "eval/association.h"

namespace vilslam::report {

TrajectoryErrors trajectory_errors(const Trajectory& est, const Trajectory& gt, eval::AlignMode mode) {
  const eval::Association matches = eval::associate(est, gt);
  const Trajectory est_matched = eval::select(est, matches.est_ids);
  const Trajectory gt_matched = eval::select(gt, matches.gt_ids);
  TrajectoryErrors e;
  e.alignment = eval::align_trajectories(est_matched, gt_matched, mode);
  e.est_in_gt_world = eval::apply_alignment(est, e.alignment);
  e.ape = eval::compute_ape(gt_matched, eval::apply_alignment(est_matched, e.alignment));
  double travelled_m = 0;
  std::size_t next = 0;  // the next matched pose (est_ids increase)
  for (std::size_t i = 0; i < est.size() && next < matches.size(); ++i) {
    if (i > 0) travelled_m += (est[i].T_W_B.translation() - est[i - 1].T_W_B.translation()).norm();
    if (matches.est_ids[next] != i) continue;
    e.t_ns.push_back(est[i].t_ns);
    e.travelled_m.push_back(travelled_m);
    ++next;
  }
  return e;
}

}  // namespace vilslam::report
