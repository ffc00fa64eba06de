#pragma once
// Loop constraints from a csv file (docs/formats.md, "Loop constraints"):
//   from_t_ns,to_t_ns,tx,ty,tz,qx,qy,qz,qw[,sigma_m,sigma_rad[,<the 16 score columns of loops.csv>]]
// The row measures T_from_to = (T_W_from)^-1 T_W_to between two poses of a trajectory (sorted by time, as
// read_trajectory returns it), found by exact time. `vilslam run` writes the long form (write_loops_csv).
#include <optional>
#include <string>
#include <vector>

#include "common/types.h"
#include "loop/loop_closer.h"
#include "loop/pose_graph.h"

namespace vilslam::loop {

// Standard deviations of a loop row that has no sigma columns.
struct LoopSigmas {
  double sigma_m = 0.05;
  double sigma_rad = 0.01;
};

// The score columns that follow the sigmas in the long form, in file order (after epnp_tx..epnp_qw).
struct LoopScores {
  double bow_score = 0, descriptor_matches = 0, pnp_inliers = 0, icp_rms_m = 0, icp_inlier_fraction = 0,
         icp_min_eigenvalue_per_match = 0, epnp_icp_translation_m = 0, epnp_icp_rotation_rad = 0,
         odometry_disagreement_m = 0;
};

struct LoopRow {
  long line = 0;
  TimeNs from_t_ns = 0;
  TimeNs to_t_ns = 0;
  SE3 T_from_to;
  std::optional<LoopSigmas> sigmas;
  std::optional<SE3> T_from_to_epnp;  // long form: the EPnP estimate before ICP
  std::optional<LoopScores> scores;
};

// Every row, checked: throws InputError naming the file and line on a missing file, a bad field count or
// a bad, non-finite field, equal from/to times, a non-unit quaternion or a non-positive sigma.
std::vector<LoopRow> read_loop_rows(const std::string& path);

// The rows as pose-graph constraints; additionally a timestamp absent from poses is an InputError.
std::vector<RelativePoseConstraint> read_loop_constraints(const std::string& path, const Trajectory& poses,
                                                          const LoopSigmas& defaults);

// loops.csv of `vilslam run`: the accepted records in the long form, with a '#' header naming the columns.
std::string loops_csv(const std::vector<LoopCandidateRecord>& records);
// loop_candidates.csv: every examined candidate, its scores and the stage that rejected it ("accepted").
std::string loop_candidates_csv(const std::vector<LoopCandidateRecord>& records);

}  // namespace vilslam::loop
