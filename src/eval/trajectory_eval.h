#pragma once
// The whole trajectory evaluation behind `vilslam eval`: associate, align, then APE, RPE, the KITTI
// segment metric, the final drift and, on request, the tilt error.
#include <cstddef>

#include "common/types.h"
#include "eval/alignment.h"
#include "eval/ape_rpe.h"
#include "eval/association.h"
#include "eval/drift.h"
#include "eval/kitti_metric.h"
#include "eval/stats.h"

namespace vilslam::eval {

struct TrajectoryEvalConfig {
  AlignMode align = AlignMode::kSe3;
  std::size_t align_first_n = 0;  // 0 = align on all matched poses
  RpeConfig rpe;
  TimeNs max_diff_ns = kDefaultMaxDiffNs;
  bool tilt = false;  // also the tilt error (eval/tilt_error.h): for gravity-aligned, z-up frames only
};

struct TrajectoryEvalReport {
  std::size_t matched_poses = 0;
  // The fraction of the reference's time span the matched poses cover (common/coverage.h): the APE and RPE are
  // over that part only.
  double reference_coverage = 0.0;
  Alignment alignment;
  PoseErrors ape;   // on the aligned estimate
  PoseErrors rpe;   // on the aligned estimate (invariant to se3/posyaw alignment; sim3 fixes the scale)
  KittiMetric kitti;
  FinalDrift fde;               // of the whole estimate (first vs last pose)
  FinalDrift fde_start_aligned; // matched poses, start poses aligned with the ground truth
  double path_length_m = 0;     // of the whole estimate
  ErrorStats tilt_deg;          // with config.tilt: of the matched poses, unaligned (count 0 otherwise)
};

// Throws std::invalid_argument when fewer than 2 poses match or a metric cannot be formed.
TrajectoryEvalReport evaluate_trajectory(const Trajectory& est, const Trajectory& gt, const TrajectoryEvalConfig& config);

}  // namespace vilslam::eval
