// The global pose graph of the running system with bounded corrections (see global_pose_graph.h and
// docs/pose_graph.md, "Bounded correction").
#include "loop/global_pose_graph.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <string>


namespace vilslam::loop {
namespace {

std::size_t lower_end(const RelativePoseConstraint& c) { return std::min(c.from_index, c.to_index); }
std::size_t upper_end(const RelativePoseConstraint& c) { return std::max(c.from_index, c.to_index); }

// Index of pose `index` in the sorted anchor list (it is one).
std::size_t anchor_slot(const std::vector<std::size_t>& anchors, std::size_t index) {
  return static_cast<std::size_t>(std::lower_bound(anchors.begin(), anchors.end(), index) - anchors.begin());
}

}  // namespace

GlobalPoseGraph::GlobalPoseGraph(const GlobalPoseGraphConfig& config)
    : config_(config),
      odometry_covariance_(information_from_sigmas(config.odometry_sigma_m, config.odometry_sigma_rad).inverse()) {
  if (config.anchor_spacing == 0 || config.max_anchors < 2 || !(config.degenerate_sigma >= 0.0) ||
      !(config.tilt_sigma_rad >= 0.0) || !(config.bearing_min_step_m >= 0.0) || !std::isfinite(config.bearing_min_step_m)) {
    throw std::invalid_argument("global pose graph: anchor_spacing must be >= 1, max_anchors >= 2, degenerate_sigma "
                                "and tilt_sigma_rad >= 0, bearing_min_step_m finite and >= 0");
  }
}

std::size_t GlobalPoseGraph::add_first_pose(TimeNs t_ns, const SE3& T_W_L) {
  if (!poses_.empty()) throw std::logic_error("global pose graph: the first pose is already added");
  poses_.push_back({t_ns, T_W_L});
  odometry_.push_back(SE3());
  step_covariances_.push_back(odometry_covariance_);
  up_L_.emplace_back();
  return 0;
}

std::size_t GlobalPoseGraph::add_odometry(TimeNs t_ns, const SE3& T_prev_cur,
                                          const std::vector<Vec6>& degenerate_directions) {
  if (poses_.empty()) throw std::logic_error("global pose graph: add_odometry before add_first_pose");
  poses_.push_back({t_ns, poses_.back().T_W_B * T_prev_cur});
  odometry_.push_back(T_prev_cur);
  Mat6 covariance = odometry_covariance_;
  const double variance = config_.degenerate_sigma * config_.degenerate_sigma;
  for (const Vec6& v : degenerate_directions) {
    const Vec6 unit = v.normalized();
    covariance += variance * unit * unit.transpose();
  }
  step_covariances_.push_back(covariance);
  up_L_.emplace_back();
  return poses_.size() - 1;
}

void GlobalPoseGraph::set_up_direction(std::size_t index, const Vec3& up_L, double sigma_rad) {
  if (index >= poses_.size() || !up_L.allFinite() || up_L.norm() < 1e-9 || !(sigma_rad >= 0.0) ||
      !std::isfinite(sigma_rad)) {
    throw std::invalid_argument("global pose graph: up direction of pose " + std::to_string(index) +
                                " is not finite and non-zero, its sigma not finite and >= 0, or the pose is not added");
  }
  up_L_[index] = MeasuredUp{up_L.normalized(), std::max(config_.tilt_sigma_rad, sigma_rad)};
}

void GlobalPoseGraph::add_loop(std::size_t from_index, std::size_t to_index, const SE3& T_from_to,
                               const Mat6& information) {
  const RelativePoseConstraint loop{from_index, to_index, T_from_to, information, ConstraintKind::kLoop};
  check_constraint(loop, poses_.size());
  loops_.push_back(loop);
  first_new_loop_pose_ = std::min(first_new_loop_pose_, lower_end(loop));
}

void GlobalPoseGraph::transform(const SE3& T_new_old) {
  for (TimedPose& p : poses_) p.T_W_B = T_new_old * p.T_W_B;
}

void GlobalPoseGraph::add_map_loop(const SE3& T_W_from, std::size_t to_index, const SE3& T_from_to,
                                   const Mat6& information) {
  if (to_index >= poses_.size()) throw std::invalid_argument("global pose graph: map loop to a pose not added");
  const RelativePoseConstraint loop{0, to_index, T_from_to, information, ConstraintKind::kLoop};
  check_constraint({0, 1, T_from_to, information}, 2);  // the information: symmetric positive definite
  map_loops_.push_back({T_W_from, loop});
  first_new_loop_pose_ = 0;
}

void GlobalPoseGraph::remove_map_loops(std::vector<std::size_t> positions) {
  std::sort(positions.begin(), positions.end());
  positions.erase(std::unique(positions.begin(), positions.end()), positions.end());
  if ((!positions.empty() && positions.back() >= map_loops_.size()) || positions.size() >= map_loops_.size()) {
    throw std::invalid_argument("global pose graph: map loops to remove must exist and leave at least one");
  }
  for (auto it = positions.rbegin(); it != positions.rend(); ++it) map_loops_.erase(map_loops_.begin() + *it);
  first_new_loop_pose_ = 0;
}

// The last pose s <= the lowest end of the new loops that no loop spans (lower end < s < upper end). Every path
// from a pose after s to a pose before it passes through s, and the factors are invariant to moving all poses
// by one rigid transform, so holding s and everything before it fixed loses nothing.
std::size_t GlobalPoseGraph::window_start() const {
  if (!map_loops_.empty()) return 0;  // the map loops hold the gauge: no pose of this run is fixed
  std::size_t start = first_new_loop_pose_;
  for (bool moved = true; moved;) {
    moved = false;
    for (const RelativePoseConstraint& c : loops_) {
      if (lower_end(c) < start && start < upper_end(c)) {
        start = lower_end(c);
        moved = true;
      }
    }
  }
  return start;
}

// Sorted anchors of the window [start, last]: its two ends, every loop end in it (map loops: start is 0), and
// every spacing-th pose, the spacing at least config_.anchor_spacing and large enough to keep those below
// config_.max_anchors.
std::vector<std::size_t> GlobalPoseGraph::select_anchors(std::size_t start, std::size_t& spacing) const {
  const std::size_t last = poses_.size() - 1;
  std::vector<std::size_t> anchors = {start, last};
  for (const RelativePoseConstraint& c : loops_) {
    if (lower_end(c) >= start) {
      anchors.push_back(c.from_index);
      anchors.push_back(c.to_index);
    }
  }
  for (const MapLoop& m : map_loops_) anchors.push_back(m.loop.to_index);
  const std::size_t length = last - start;
  spacing = std::max(config_.anchor_spacing, (length + config_.max_anchors - 1) / config_.max_anchors);
  for (std::size_t i = (start / spacing + 1) * spacing; i < last; i += spacing) anchors.push_back(i);
  std::sort(anchors.begin(), anchors.end());
  anchors.erase(std::unique(anchors.begin(), anchors.end()), anchors.end());
  return anchors;
}

CorrectionSummary GlobalPoseGraph::optimize() {
  return solve(config_.tilt_sigma_rad > 0.0 && !config_.tilt_final_only);
}

CorrectionSummary GlobalPoseGraph::optimize_final() {
  if (!config_.tilt_final_only || config_.tilt_sigma_rad <= 0.0 || (loops_.empty() && map_loops_.empty())) return {};
  first_new_loop_pose_ = map_loops_.empty() ? poses_.size() - 1 : 0;
  for (const RelativePoseConstraint& c : loops_) first_new_loop_pose_ = std::min(first_new_loop_pose_, lower_end(c));
  return solve(true);
}

CorrectionSummary GlobalPoseGraph::solve(bool with_tilt) {
  CorrectionSummary summary;
  if (first_new_loop_pose_ == kNone) return summary;
  const auto t0 = std::chrono::steady_clock::now();
  const std::size_t start = window_start();
  const std::vector<std::size_t> anchors = select_anchors(start, summary.anchor_spacing);

  // The reduced graph: anchors (the window's first pose is its fixed gauge; with map loops the map poses are,
  // placed before the anchors), one composed factor per chain between consecutive anchors, and the window's loops.
  PoseGraph reduced;
  for (const MapLoop& m : map_loops_) reduced.add_pose(0, m.T_W_from, true);
  const std::size_t first = reduced.poses().size();  // slot of anchors[0]
  const auto slot = [&](std::size_t index) { return first + anchor_slot(anchors, index); };
  for (std::size_t a : anchors) reduced.add_pose(poses_[a].t_ns, poses_[a].T_W_B);
  for (std::size_t k = 0; k + 1 < anchors.size(); ++k) {
    const ComposedChain chain = compose_chain(odometry_, step_covariances_, anchors[k], anchors[k + 1]);
    const Mat6 information = chain.covariance.inverse();
    reduced.add_constraint({first + k, first + k + 1, chain.T_a_b, 0.5 * (information + information.transpose()),
                            ConstraintKind::kOdometry});
  }
  for (const RelativePoseConstraint& c : loops_) {
    if (lower_end(c) < start) continue;
    reduced.add_constraint({slot(c.from_index), slot(c.to_index), c.T_from_to, c.information, ConstraintKind::kLoop});
  }
  for (std::size_t m = 0; m < map_loops_.size(); ++m) {
    const RelativePoseConstraint& c = map_loops_[m].loop;
    reduced.add_constraint({m, slot(c.to_index), c.T_from_to, c.information, ConstraintKind::kLoop});
  }
  if (with_tilt) {
    for (std::size_t k = map_loops_.empty() ? 1 : 0; k < anchors.size(); ++k) {  // a fixed first pose needs none
      if (const auto& up = up_L_[anchors[k]]) reduced.add_tilt({first + k, up->up_L, up->sigma_rad});
    }
  }
  PoseGraphOptions options;
  options.loop_loss = config_.loop_loss;
  options.loop_loss_scale = config_.loop_loss_scale;
  options.max_iterations = config_.max_iterations;
  options.bearing_min_step_m = config_.bearing_min_step_m;
  const PoseGraphSummary solved = reduced.optimize(options);

  for (std::size_t k = 0; k < anchors.size(); ++k) poses_[anchors[k]].T_W_B = reduced.poses()[first + k].T_W_B;
  for (std::size_t k = 0; k + 1 < anchors.size(); ++k) {
    correct_chain_interior(odometry_, step_covariances_, anchors[k], anchors[k + 1], poses_);
  }
  first_new_loop_pose_ = kNone;

  summary.variables = anchors.size() - (map_loops_.empty() ? 1 : 0);
  summary.moved_poses = poses_.size() - (map_loops_.empty() ? 1 : 0) - start;
  summary.iterations = solved.iterations;
  summary.converged = solved.converged;
  summary.initial_cost = solved.initial_cost;
  summary.final_cost = solved.final_cost;
  summary.solve_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  return summary;
}

}  // namespace vilslam::loop
