#pragma once
// Final drift error (FDE), the paper's measure for runs that start and end at the same place:
// the distance between the first and the last estimated position, relative to the estimated path length.
#include "common/types.h"

namespace vilslam::eval {

// Sum of the distances between consecutive positions.
double path_length_m(const Trajectory& traj);

struct FinalDrift {
  double drift_m = 0;       // distance between the two compared positions
  double path_length_m = 0; // length the drift is relative to
  double percent = 0;       // 100 drift / path length (0 for a zero-length path)
};

// |p_last - p_first| of the estimate over its path length.
FinalDrift final_drift(const Trajectory& est);

// With ground truth: the estimate is moved rigidly so that its first pose equals the first
// ground-truth pose (T = Q_0 P_0^-1); the drift is the distance between the moved last estimated
// position and the last ground-truth position, over the ground-truth path length. gt[i] and est[i]
// correspond; throws std::invalid_argument on a length mismatch or empty input.
FinalDrift final_drift_start_aligned(const Trajectory& gt, const Trajectory& est);

}  // namespace vilslam::eval
