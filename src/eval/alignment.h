#pragma once
// Aligning an estimated trajectory to the ground truth before computing absolute errors.
//   se3:    rotation + translation (Umeyama 1991 without scale, as evo's -a)
//   sim3:   rotation + translation + scale (Umeyama 1991, as evo's -as), for monocular estimates
//   posyaw: yaw about the gravity axis z + translation (4-DoF), the unobservable directions of VIO
//   none:   identity
#include <cstddef>
#include <string>
#include <vector>

#include "common/types.h"

namespace vilslam::eval {

enum class AlignMode { kSe3, kSim3, kPosYaw, kNone };

// "se3" | "sim3" | "posyaw" | "none"; throws std::invalid_argument otherwise.
AlignMode parse_align_mode(const std::string& name);
std::string align_mode_name(AlignMode mode);

// p_gt ~= scale * T_gt_est.rotation() * p_est + T_gt_est.translation().
struct Alignment {
  AlignMode mode = AlignMode::kNone;
  double scale = 1.0;
  SE3 T_gt_est;
};

// Least-squares alignment of corresponding positions (same count, at least 3 for se3/sim3, 2 for posyaw).
// Throws std::invalid_argument on a count mismatch or a degenerate point set.
Alignment align_positions(const std::vector<Vec3>& p_est, const std::vector<Vec3>& p_gt, AlignMode mode);

// Aligns matched trajectories (est[i] corresponds to gt[i]) on their first `first_n` poses (0 = all).
Alignment align_trajectories(const Trajectory& est, const Trajectory& gt, AlignMode mode, std::size_t first_n = 0);

// Applies the alignment to every pose: R -> R_a R, t -> s R_a t + t_a (evo scales, then transforms).
Trajectory apply_alignment(const Trajectory& est, const Alignment& alignment);

}  // namespace vilslam::eval
