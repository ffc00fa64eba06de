#include "eval/trajectory_eval.h"

#include <stdexcept>
#include <string>

#include "common/coverage.h"
#include "eval/tilt_error.h"

namespace vilslam::eval {

TrajectoryEvalReport evaluate_trajectory(const Trajectory& est, const Trajectory& gt, const TrajectoryEvalConfig& config) {
  const Association assoc = associate(est, gt, config.max_diff_ns);
  if (assoc.size() < 2) {
    throw std::invalid_argument("only " + std::to_string(assoc.size()) +
                                " poses match in time; check the timestamps and --max-diff");
  }
  const Trajectory gt_matched = select(gt, assoc.gt_ids);
  const Trajectory est_matched = select(est, assoc.est_ids);
  TrajectoryEvalReport r;
  r.matched_poses = assoc.size();
  std::vector<TimeNs> matched_t_ns;
  for (const TimedPose& p : gt_matched) matched_t_ns.push_back(p.t_ns);
  r.reference_coverage = coverage_of(matched_t_ns, std::vector<bool>(matched_t_ns.size(), true),
                                     ns_to_s(gt.back().t_ns - gt.front().t_ns)).published;
  r.alignment = align_trajectories(est_matched, gt_matched, config.align, config.align_first_n);
  const Trajectory est_aligned = apply_alignment(est_matched, r.alignment);
  r.ape = compute_ape(gt_matched, est_aligned);
  r.rpe = compute_rpe(gt_matched, est_aligned, config.rpe);
  r.kitti = compute_kitti_metric(gt_matched, est_aligned);
  r.fde = final_drift(est);
  r.fde_start_aligned = final_drift_start_aligned(gt_matched, est_matched);
  r.path_length_m = r.fde.path_length_m;
  if (config.tilt) r.tilt_deg = compute_stats(tilt_errors_deg(gt_matched, est_matched));
  return r;
}

}  // namespace vilslam::eval
