#pragma once
// An estimate against the ground truth, pose by pose, for the report's error-over-time and -distance plots:
// associated and aligned as `vilslam eval` does (eval/association.h, eval/alignment.h), then each matched
// pose's absolute error (eval/ape_rpe.h).
#include <vector>

#include "common/types.h"
#include "eval/alignment.h"
#include "eval/ape_rpe.h"

namespace vilslam::report {

struct TrajectoryErrors {
  eval::Alignment alignment;
  Trajectory est_in_gt_world;        // every pose of the estimate, aligned into the ground truth's world
  std::vector<TimeNs> t_ns;          // of the matched poses
  std::vector<double> travelled_m;   // the estimate's path length from its first pose to each matched pose
  eval::PoseErrors ape;              // per matched pose
};

// Throws std::invalid_argument when too few poses match for the alignment.
TrajectoryErrors trajectory_errors(const Trajectory& est, const Trajectory& gt, eval::AlignMode mode);

}  // namespace vilslam::report
