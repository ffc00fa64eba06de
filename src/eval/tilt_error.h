#pragma once
// Tilt error: how far an estimate's roll and pitch are from the ground truth's, free of yaw and position.
//   tilt_i = angle(R(P_i)^T e_z, R(Q_i)^T e_z)   (estimate P, reference Q, both in z-up gravity-aligned frames)
// the angle between the two bodies' measured up directions, in degrees. No alignment enters: an SE(3) fit
// would rotate the estimate's frame and trade its tilt against its positions, while both frames already share
// the vertical by construction (a VIO's world and a simulator's truth).
#include <vector>

#include "common/types.h"

namespace vilslam::eval {

// gt[i] and est[i] correspond (associated). Throws std::invalid_argument on a length mismatch or empty input.
std::vector<double> tilt_errors_deg(const Trajectory& gt, const Trajectory& est);

}  // namespace vilslam::eval
