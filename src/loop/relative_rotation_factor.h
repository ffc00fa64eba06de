#pragma once
// A relative-rotation factor of the global pose graph, templated for Ceres autodiff: the VIO's rotation between
// two poses (gyro-integrated, far more precise over a few seconds than the LiDAR odometry's) measured as q_a_b.
// Pose blocks as in relative_pose_factor.h; the positions are not touched.
#include <ceres/rotation.h>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "common/lie.h"

namespace vilslam::loop {

class RelativeRotationFactor {
 public:
  RelativeRotationFactor(const Quat& q_a_b, double sigma_rad) : q_b_a_(q_a_b.conjugate()), weight_(1.0 / sigma_rad) {}

  // r = Log(q_a_b^-1 q_W_a^-1 q_W_b) / sigma.
  template <typename T>
  bool operator()(const T* pose_a, const T* pose_b, T* residual) const {
    const Eigen::Map<const Eigen::Quaternion<T>> q_W_a(pose_a);
    const Eigen::Map<const Eigen::Quaternion<T>> q_W_b(pose_b);
    const Eigen::Quaternion<T> q_err = q_b_a_.cast<T>() * (q_W_a.conjugate() * q_W_b);
    const T q_wxyz[4] = {q_err.w(), q_err.x(), q_err.y(), q_err.z()};
    ceres::QuaternionToAngleAxis(q_wxyz, residual);
    for (int i = 0; i < 3; ++i) residual[i] *= T(weight_);
    return true;
  }

 private:
  Quat q_b_a_;
  double weight_;
};

}  // namespace vilslam::loop
