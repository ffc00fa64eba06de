#pragma once
// How well a segment after a reset was joined to the map of the segments before it (run --reset-at; docs/loop.md,
// "Forced resets"): the relative pose from the last final pose before the reset to the first one joined, against
// the true one; and the ground truth fitted (SE(3)) to the final poses in a window before the reset, so only the
// map around the junction counts, not the drift elsewhere, with the joined segment's positions in a window from
// its join on compared with it, unaligned.
#include <cstddef>

#include "common/types.h"

namespace vilslam::eval {

struct JoinError {
  // The junction: the relative pose from the last final pose before the reset to the first one from the join on,
  // against the true one (no fit).
  double junction_translation_m = 0, junction_rotation_deg = 0;
  // The window: positions from the join on against the truth fitted before the reset (a fit to a short stretch
  // of route leaves its rotation weak, so only positions are compared).
  std::size_t fitted_poses = 0;  // before the reset
  std::size_t joined_poses = 0;  // compared, from the join on
  double max_translation_m = 0, rmse_translation_m = 0;
};

// est_T_W_L: the run's lidar_final.tum (every segment, joined ones in the map's frame); gt_T_W_L: true LiDAR
// poses; both sorted by time. The compared window ends at end_t_ns at the latest (the next reset). Throws
// std::invalid_argument when fewer than 3 poses lie in the window before the reset or none in the one after
// the join.
JoinError join_error(const Trajectory& est_T_W_L, const Trajectory& gt_T_W_L, TimeNs reset_t_ns, TimeNs joined_t_ns,
                     TimeNs end_t_ns, double window_s);

}  // namespace vilslam::eval
