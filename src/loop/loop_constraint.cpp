#include "loop/loop_constraint.h"

namespace vilslam::loop {

SE3 lidar_constraint_from_camera(const SE3& T_C0v_C0u, const SE3& T_Lu_C0u, const SE3& T_Lv_C0v) {
  return T_Lu_C0u * T_C0v_C0u.inverse() * T_Lv_C0v.inverse();
}

PoseDifference pose_difference(const SE3& a, const SE3& b) {
  const SE3 d = a.inverse() * b;
  return {d.translation().norm(), so3::log(d.quat()).norm()};
}

}  // namespace vilslam::loop
