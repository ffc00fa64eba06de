#pragma once
// Frames of the loop constraint (paper, "Loop constraint"): the visual constraint between the key images'
// left cameras moved into the key scans' frames, and the size of the difference of two poses.
#include "common/lie.h"

namespace vilslam::loop {

// T_Lu_Lv = T_Lu_C0u * T_C0v_C0u^-1 * T_Lv_C0v^-1 (u the candidate, v the query).
SE3 lidar_constraint_from_camera(const SE3& T_C0v_C0u, const SE3& T_Lu_C0u, const SE3& T_Lv_C0v);

// Translation (m) and rotation angle (rad) of a^-1 b.
struct PoseDifference {
  double translation_m = 0.0;
  double rotation_rad = 0.0;
};
PoseDifference pose_difference(const SE3& a, const SE3& b);

}  // namespace vilslam::loop
