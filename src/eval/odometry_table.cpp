#include "eval/odometry_table.h"

#include <algorithm>
#include <cstdio>
#include <limits>
#include <stdexcept>

#include "eval/drift.h"
#include "eval/trajectory_eval.h"

namespace vilslam::eval {
namespace {

std::string format(const char* fmt, double a, double b) {
  char buf[160];
  std::snprintf(buf, sizeof buf, fmt, a, b);
  return buf;
}

bool finite_poses(const Trajectory& traj) {
  return std::all_of(traj.begin(), traj.end(), [](const TimedPose& p) {
    return p.T_W_B.translation().allFinite() && p.T_W_B.quat().coeffs().allFinite();
  });
}

double span_s(const Trajectory& traj) { return ns_to_s(traj.back().t_ns - traj.front().t_ns); }

double end_to_start_gap_m(const Trajectory& traj) {
  return (traj.back().T_W_B.translation() - traj.front().T_W_B.translation()).norm();
}

// NaN when the positions do not fix an SE(3) alignment (all on one line).
double ate_se3_rmse_m(const Trajectory& est, const Trajectory& gt) {
  TrajectoryEvalConfig config;
  config.align = AlignMode::kSe3;
  try {
    return evaluate_trajectory(est, gt, config).ape.trans.rmse;
  } catch (const std::invalid_argument&) {
    return std::numeric_limits<double>::quiet_NaN();
  }
}

}  // namespace

DriftResult evaluate_drift(const RunTrajectory& run, const Trajectory& gt, AlignMode align, bool closed,
                           const LostCriteria& criteria) {
  DriftResult r;
  r.align = align;
  r.poses = run.poses.size();
  const auto lost = [&r](std::string reason) {
    r.lost = true;
    r.lost_reason = std::move(reason);
    return r;
  };
  if (!run.failure.empty()) return lost("the run failed: " + run.failure);
  if (run.poses.size() < 2) return lost("fewer than 2 poses");
  if (!finite_poses(run.poses)) return lost("a pose is not finite");
  TrajectoryEvalConfig config;
  config.align = align;
  TrajectoryEvalReport report;
  try {
    report = evaluate_trajectory(run.poses, gt, config);
  } catch (const std::invalid_argument& e) {
    return lost(std::string("not comparable with ground truth: ") + e.what());
  }
  const FinalDrift& fde = closed ? report.fde : report.fde_start_aligned;
  r.fde_percent = fde.percent;
  r.drift_m = fde.drift_m;
  r.path_length_m = fde.path_length_m;
  r.ate_rmse_m = report.ape.trans.rmse;
  r.ape_max_m = report.ape.trans.max;
  r.ate_se3_rmse_m = align == AlignMode::kSe3 ? r.ate_rmse_m : ate_se3_rmse_m(run.poses, gt);
  const double coverage = span_s(run.poses) / span_s(gt);
  if (coverage < criteria.min_coverage)
    return lost(format("covers %.0f %% of the sequence (less than %.0f %%)", 100 * coverage, 100 * criteria.min_coverage));
  const double limit_m = std::max(criteria.max_error_floor_m, criteria.max_error_fraction * path_length_m(gt));
  if (r.ape_max_m > limit_m) return lost(format("strays %.2f m from ground truth (limit %.2f m)", r.ape_max_m, limit_m));
  return r;
}

OdometryRow compute_odometry_row(const OdometryInputs& in, const LostCriteria& criteria) {
  if (in.gt_T_W_I.size() < 2 || in.gt_T_W_L.size() < 2)
    throw std::invalid_argument("odometry row of " + in.preset + ": ground truth has fewer than 2 poses");
  OdometryRow row;
  row.preset = in.preset;
  row.source = in.source;
  row.gt_length_m = path_length_m(in.gt_T_W_I);
  row.gt_gap_m = std::max(end_to_start_gap_m(in.gt_T_W_I), end_to_start_gap_m(in.gt_T_W_L));
  row.closed = row.gt_gap_m <= kClosedRouteGapM;
  // The VIO and VIL share the gravity-aligned VIO world (yaw and position unobservable); LiDAR-only
  // starts in the first sweep's frame, so it is aligned in SE(3).
  row.vio = evaluate_drift(in.vio, in.gt_T_W_I, AlignMode::kPosYaw, row.closed, criteria);
  row.vil = evaluate_drift(in.vil, in.gt_T_W_L, AlignMode::kPosYaw, row.closed, criteria);
  row.lidar_only = evaluate_drift(in.lidar_only, in.gt_T_W_L, AlignMode::kSe3, row.closed, criteria);
  row.vil_final = evaluate_drift(in.vil_final, in.gt_T_W_L, AlignMode::kPosYaw, row.closed, criteria);
  if (in.loops) row.loops = LoopClosureResult{in.loops->candidates_examined, evaluate_loops(in.loops->accepted, in.gt_T_W_L)};
  row.vil_degenerate = in.vil_degenerate;
  row.vil_sweeps = in.vil_sweeps;
  row.lidar_only_degenerate = in.lidar_only_degenerate;
  row.lidar_only_sweeps = in.lidar_only_sweeps;
  return row;
}

std::optional<PaperOdometry> paper_odometry(const std::string& preset) {
  // VIL-SLAM paper, Table I "FDE (%) and MRE (m) test results" (odometry FDE before loop closure, MRE of
  // VIL-SLAM and LOAM); FDE after loop closure from the text of its "Experimental results" section.
  const std::nullopt_t none = std::nullopt;
  if (preset == "highbay") return PaperOdometry{"Highbay", 118, 0.08, 0.56, none, "closes the loop, no FDE given", 0.08, 0.22};
  if (preset == "hallway") return PaperOdometry{"Hallway", 103, 0.61, 0.91, 0.05, "", 0.10, 0.27};
  if (preset == "tunnel") return PaperOdometry{"Tunnel", 85, 1.86, none, 0.08, "", none, none};
  if (preset == "loop") return PaperOdometry{"Huge Loop", 318, 0.01, none, none, "no loop triggered", 0.22, 0.36};
  if (preset == "outdoor") return PaperOdometry{"Outdoor", 528, 0.02, 0.02, none, "", none, none};
  return std::nullopt;
}

}  // namespace vilslam::eval
