#pragma once
// The global pose graph of the running system (paper Fig. 3): every LiDAR mapping pose, a LiDAR odometry
// factor between consecutive poses and loop factors with a robust loss. The paper solves it with iSAM2;
// here each correction re-optimizes a bounded problem (docs/pose_graph.md): the cost of one correction
// must stay bounded as the graph grows (bench/global_pose_graph.cpp, up to 20,000 poses).
#include <cstddef>

#include "common/lie.h"
#include "common/types.h"
#include "loop/pose_graph.h"

namespace vilslam::loop {

struct GlobalPoseGraphConfig {
  double odometry_sigma_m = 0.01;     // per LiDAR odometry factor (one sweep)
  double odometry_sigma_rad = 0.001;
  RobustLoss loop_loss = RobustLoss::kHuber;
  double loop_loss_scale = 1.0;       // whitened units
  int max_iterations = 50;
};

struct CorrectionSummary {
  double solve_ms = 0.0;       // wall time of optimize()
  std::size_t variables = 0;   // pose blocks optimized
  int iterations = 0;
  bool converged = false;
  double initial_cost = 0.0;
  double final_cost = 0.0;
};

class GlobalPoseGraph {
 public:
  explicit GlobalPoseGraph(const GlobalPoseGraphConfig& config = {});

  // The first pose fixes the gauge. Later poses come with the measured LiDAR odometry since the previous
  // pose; the new pose's estimate is the previous pose's current estimate composed with it. Returns its index.
  std::size_t add_first_pose(TimeNs t_ns, const SE3& T_W_L);
  std::size_t add_odometry(TimeNs t_ns, const SE3& T_prev_cur);
  // A loop factor measuring T_from_to = (T_W_from)^-1 T_W_to; throws std::invalid_argument on a bad index
  // or an information matrix that is not symmetric positive definite.
  void add_loop(std::size_t from_index, std::size_t to_index, const SE3& T_from_to, const Mat6& information);

  // Corrects every pose with the factors known now. Deterministic.
  CorrectionSummary optimize();

  std::size_t size() const;
  const SE3& pose(std::size_t index) const;   // current best estimate T_W_L
  Trajectory trajectory() const;              // all poses with their times
};

}  // namespace vilslam::loop
