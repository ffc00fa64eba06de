#pragma once
// A gravity-tilt factor of the global pose graph, templated for Ceres autodiff: the VIO measures roll and pitch
// against gravity without drift, so each pose's up direction in its own frame, R_W_L^T e_z, is pulled towards the
// VIO's. Yaw and position stay free (they are not observable from gravity). Pose block as relative_pose_factor.h.
#include <Eigen/Core>
#include <Eigen/Geometry>

#include "common/lie.h"

namespace vilslam::loop {

class TiltFactor {
 public:
  TiltFactor(const Vec3& up_L_measured, double sigma_rad) : up_L_(up_L_measured.normalized()), weight_(1.0 / sigma_rad) {}

  // r = (R_W_L^T e_z - up_L) / sigma: for small errors its norm is the tilt error's angle over sigma, and it has
  // no component along up_L (rank 2, as roll and pitch).
  template <typename T>
  bool operator()(const T* pose, T* residual) const {
    const Eigen::Matrix<T, 3, 1> up_measured = up_L_.cast<T>();
    const Eigen::Map<const Eigen::Quaternion<T>> q_W_L(pose);
    const Eigen::Matrix<T, 3, 1> up_est = q_W_L.conjugate() * Eigen::Matrix<T, 3, 1>::UnitZ();
    Eigen::Map<Eigen::Matrix<T, 3, 1>> r(residual);
    r = (up_est - up_measured) * T(weight_);
    return true;
  }

 private:
  Vec3 up_L_;
  double weight_;
};

}  // namespace vilslam::loop
