#pragma once
// Absolute and relative pose errors, defined as evo defines them.
//   APE_i = P_i^-1 Q_i (estimate P, reference Q): translation part |t(P_i) - t(Q_i)|, rotation part
//           the angle of its rotation in degrees.
//   RPE_ij = (Q_i^-1 Q_j)^-1 (P_i^-1 P_j) over pose pairs (i, j): translation part |t(RPE_ij)|,
//           rotation part its angle in degrees.
#include <cstddef>
#include <utility>
#include <vector>

#include "common/types.h"
#include "eval/stats.h"

namespace vilslam::eval {

struct PoseErrors {
  std::vector<double> trans_m;  // one per pose (APE) or pair (RPE)
  std::vector<double> rot_deg;
  ErrorStats trans;
  ErrorStats rot;
};

// gt[i] and est[i] correspond (associated and, for APE, est already aligned). Throws std::invalid_argument
// on a length mismatch or empty input.
PoseErrors compute_ape(const Trajectory& gt, const Trajectory& est);

enum class DeltaUnit { kFrames, kMeters };

struct RpeConfig {
  double delta = 1.0;  // frames (a positive integer) or metres of travelled path
  DeltaUnit unit = DeltaUnit::kFrames;
};

// evo's consecutive pose pairs (pairs_from_reference = false: chosen on the estimate):
//   frames: ids 0, d, 2d, ...;  metres: ids where the path accumulated since the previous id reaches d
//   (counting from pose 0, which is not itself an id); pairs are consecutive ids.
std::vector<std::pair<std::size_t, std::size_t>> rpe_pairs(const Trajectory& poses, const RpeConfig& config);

// Throws std::invalid_argument when the delta yields no pair.
PoseErrors compute_rpe(const Trajectory& gt, const Trajectory& est, const RpeConfig& config);

}  // namespace vilslam::eval
