#pragma once
// The global pose graph of the running system (paper Fig. 3): every LiDAR mapping pose, a LiDAR odometry
// factor between consecutive poses and loop factors with a robust loss. The paper solves it with iSAM2;
// here each correction re-optimizes a bounded problem (docs/pose_graph.md, "Bounded correction"): only the
// poses after the last cut pose before the new loops move, the solver sees only anchor poses (loop ends and
// every k-th pose) joined by composed odometry chains, and the poses between anchors follow their chain.
// The cost of one correction stays bounded as the graph grows (bench/global_pose_graph.cpp, up to 20,000 poses).
#include <cstddef>
#include <limits>
#include <optional>
#include <vector>

#include "common/lie.h"
#include "common/types.h"
#include "loop/odometry_chain.h"
#include "loop/pose_graph.h"

namespace vilslam::loop {

struct GlobalPoseGraphConfig {
  double odometry_sigma_m = 0.01;     // per LiDAR odometry factor (one sweep)
  double odometry_sigma_rad = 0.001;
  // Added sigma along each direction the sweep's registration left unconstrained: there the mapper kept the
  // VIO's motion (a corridor's axis), which drifts more, so a loop's correction goes mostly there. Chosen on
  // the tuning seed 2 of the loop preset (docs/pose_graph.md); 0 = every sweep alike.
  double degenerate_sigma = 0.1;
  // Sigma of the gravity-tilt factor on each anchor with a measured up direction (set_up_direction, the VIO's);
  // 0 = none. Without it a loop can bend the route in roll and pitch to fit one tilted key frame. Chosen on the
  // tuning seeds 1, 2 and 7 (docs/pose_graph.md, "Tilt factors from the VIO").
  double tilt_sigma_rad = 0.005;
  // The tilt factors only in the final solve (optimize_final, lidar_final.tum), not in the corrections fed back to
  // LiDAR mapping: a correction that levels the route also tilts the old map under a revisit, whose published poses
  // then lie off the first visit's as published (issue 9 item 4). On by default since 2026-12-07 for that, at about
  // 1 % of final ATE on the tuning routes (docs/pose_graph.md, "Levelling only at the end").
  bool tilt_final_only = true;
  // Odometry chains that move at least this far (m) are compared as a length and a bearing, the bearing's error at
  // the measured length; 0 = off. Otherwise a pose held pitched against its level step (a mount's pitch in the tilt
  // factors) leaves a residual across the step that shrinks with its length, and a degenerate step's length is
  // cheap: both legs of a corridor shorten (docs/pose_graph.md, "Length and bearing of a step"). 0.05 by default
  // since 2026-12-07, with the frontend's klt_final_window_px 11: alone it was rejected twice, as the shortening
  // offset the frontend's long legs (docs/frontend.md, "A small final KLT window").
  double bearing_min_step_m = 0.05;
  RobustLoss loop_loss = RobustLoss::kHuber;
  // Whitened units. 1 bounds a wrong loop's pull best; 3.5 converges in fewer iterations but lets a wrong
  // loop pull 4x harder (docs/pose_graph.md, "Bounded correction").
  double loop_loss_scale = 1.0;
  int max_iterations = 50;
  std::size_t anchor_spacing = 10;    // poses between anchors at least (1 s of sweeps at 10 Hz); 1 = batch
  std::size_t max_anchors = 400;      // spacing grows so the anchors besides loop ends stay below this
};

struct CorrectionSummary {
  double solve_ms = 0.0;       // wall time of optimize()
  std::size_t variables = 0;   // pose blocks optimized (anchors after the window's fixed first pose)
  std::size_t moved_poses = 0; // poses after the window's first pose, all re-estimated
  std::size_t anchor_spacing = 0;
  int iterations = 0;
  bool converged = false;
  double initial_cost = 0.0;
  double final_cost = 0.0;
};

class GlobalPoseGraph {
 public:
  // Throws std::invalid_argument on non-positive sigmas, anchor_spacing 0 or max_anchors < 2.
  explicit GlobalPoseGraph(const GlobalPoseGraphConfig& config = {});

  // The first pose fixes the gauge. Later poses come with the measured LiDAR odometry since the previous
  // pose; the new pose's estimate is the previous pose's current estimate composed with it. Returns its index.
  // std::logic_error on add_first_pose twice or add_odometry before it.
  std::size_t add_first_pose(TimeNs t_ns, const SE3& T_W_L);
  // degenerate_directions: unit [rho; phi] directions in the current frame that the sweep's registration did
  // not constrain (lidar::LidarMappingResult); each adds config.degenerate_sigma^2 v v^T to the step's covariance.
  std::size_t add_odometry(TimeNs t_ns, const SE3& T_prev_cur, const std::vector<Vec6>& degenerate_directions = {});
  // The pose's up direction R_W_L^T e_z as measured against gravity (the VIO's at the same instant); used when
  // config.tilt_sigma_rad > 0, with the larger of that sigma and the measurement's own (sigma_rad, the VIO's
  // tilt standard deviation when known). Throws std::invalid_argument on a bad index or a non-finite or zero
  // vector.
  void set_up_direction(std::size_t index, const Vec3& up_L, double sigma_rad = 0.0);
  // A loop factor measuring T_from_to = (T_W_from)^-1 T_W_to; throws std::invalid_argument on a bad index
  // or an information matrix that is not symmetric positive definite.
  void add_loop(std::size_t from_index, std::size_t to_index, const SE3& T_from_to, const Mat6& information);

  // Re-localization in a loaded map (docs/loop.md, "Map reuse"). transform moves every pose rigidly,
  // T_W_L <- T_new_old T_W_L (the factors do not change: they are relative). add_map_loop adds a loop from a
  // map pose T_W_from that stays as it is to pose to_index; once the graph has one, every correction
  // optimizes all poses, their gauge given by the map loops rather than by a fixed pose of this run.
  void transform(const SE3& T_new_old);
  void add_map_loop(const SE3& T_W_from, std::size_t to_index, const SE3& T_from_to, const Mat6& information);
  std::size_t map_loops() const { return map_loops_.size(); }
  // Drops the map loops at these positions (in the order they were added; later ones move up); the next optimize()
  // re-estimates every pose. Throws std::invalid_argument on a position out of range or when no map loop would stay
  // (they hold the gauge).
  void remove_map_loops(std::vector<std::size_t> positions);

  // Corrects every pose with the factors known now (nothing to do without a new loop). Deterministic.
  CorrectionSummary optimize();
  // With config.tilt_final_only and at least one loop: the window of every loop solved again, with the tilt factors
  // (the final trajectory); nothing to do otherwise.
  CorrectionSummary optimize_final();

  std::size_t size() const { return poses_.size(); }
  const SE3& pose(std::size_t index) const { return poses_.at(index).T_W_B; }  // current best estimate T_W_L
  const Trajectory& trajectory() const { return poses_; }                      // all poses with their times

 private:
  static constexpr std::size_t kNone = std::numeric_limits<std::size_t>::max();

  std::size_t window_start() const;
  CorrectionSummary solve(bool with_tilt);
  std::vector<std::size_t> select_anchors(std::size_t start, std::size_t& spacing) const;

  GlobalPoseGraphConfig config_;
  Mat6 odometry_covariance_;  // of a sweep with no degenerate direction
  Trajectory poses_;
  std::vector<SE3> odometry_;  // odometry_[i] = measured T_{i-1,i}; odometry_[0] unused
  Mat6List step_covariances_;  // of odometry_[i]
  struct MeasuredUp {
    Vec3 up_L;
    double sigma_rad;  // of the tilt factor
  };
  std::vector<std::optional<MeasuredUp>> up_L_;  // measured up direction per pose
  std::vector<RelativePoseConstraint> loops_;
  struct MapLoop {
    SE3 T_W_from;
    RelativePoseConstraint loop;  // from_index unused
  };
  std::vector<MapLoop> map_loops_;
  std::size_t first_new_loop_pose_ = kNone;  // lowest pose touched by a loop added since the last optimize()
};

}  // namespace vilslam::loop
