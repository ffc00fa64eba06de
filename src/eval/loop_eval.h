#pragma once
// Accuracy of loop constraints against ground truth (`vilslam eval-loops`, docs/evaluation.md): each
// constraint T_from_to of two LiDAR poses is compared with the true relative pose of the same instants;
// a loop is false when its error exceeds 0.3 m or 3 degrees (issue "Loop closure in the pipeline").
#include <optional>
#include <string>
#include <vector>

#include "common/types.h"

namespace vilslam::eval {

struct LoopToEvaluate {
  TimeNs from_t_ns = 0;
  TimeNs to_t_ns = 0;
  SE3 T_from_to;                      // the constraint (EPnP + ICP)
  std::optional<SE3> T_from_to_epnp;  // EPnP alone, when known
};

struct LoopError {
  double translation_m = 0;
  double rotation_deg = 0;
  std::optional<double> epnp_translation_m;
  std::optional<double> epnp_rotation_deg;
  bool is_false = false;
};

struct LoopErrorCriteria {
  double false_translation_m = 0.3;
  double false_rotation_deg = 3.0;
};

struct LoopEvaluation {
  std::vector<LoopError> loops;  // in input order
  int true_loops = 0;
  int false_loops = 0;
  // Medians over all loops (0 when there are none); the EPnP ones over loops that carry an EPnP estimate.
  double median_translation_m = 0, median_rotation_deg = 0;
  double median_epnp_translation_m = 0, median_epnp_rotation_deg = 0;
};

// gt_T_W_L: true LiDAR poses, sorted by time, spanning every loop's instants (interpolated between
// samples); a loop instant outside the span throws std::invalid_argument.
LoopEvaluation evaluate_loops(const std::vector<LoopToEvaluate>& loops, const Trajectory& gt_T_W_L,
                              const LoopErrorCriteria& criteria = {});

std::string loop_evaluation_json(const LoopEvaluation& e, const std::vector<LoopToEvaluate>& loops);

}  // namespace vilslam::eval
