#pragma once
// The relative-pose factor of the global pose graph (odometry and loop factors alike), templated for Ceres
// autodiff. A pose parameter block is [qx qy qz qw tx ty tz] of T_W_L (Eigen's quaternion storage order).
#include <ceres/rotation.h>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "common/lie.h"

namespace vilslam::loop {

constexpr int kPoseBlockSize = 7;

// xi = [rho; phi] = Log(q, t) on SE(3), same convention as SE3::log (rho = Jl(phi)^-1 t).
template <typename T>
Eigen::Matrix<T, 6, 1> se3_log(const Eigen::Quaternion<T>& q, const Eigen::Matrix<T, 3, 1>& t) {
  const T q_wxyz[4] = {q.w(), q.x(), q.y(), q.z()};
  Eigen::Matrix<T, 3, 1> phi;
  ceres::QuaternionToAngleAxis(q_wxyz, phi.data());
  const T theta_sq = phi.squaredNorm();
  // Jl^-1(phi) = I - 1/2 [phi]x + c [phi]x^2, the closed form of so3::left_jacobian_inv, with
  // c = 1/theta^2 - (1 + cos theta) / (2 theta sin theta), whose series is 1/12 + theta^2/720 near 0.
  T c;
  if (theta_sq < T(1e-6)) {
    c = T(1.0 / 12.0) + theta_sq / T(720.0);
  } else {
    using std::cos;
    using std::sin;
    using std::sqrt;
    const T theta = sqrt(theta_sq);
    c = T(1.0) / theta_sq - (T(1.0) + cos(theta)) / (T(2.0) * theta * sin(theta));
  }
  const Eigen::Matrix<T, 3, 1> phi_x_t = phi.cross(t);
  Eigen::Matrix<T, 6, 1> xi;
  xi.template head<3>() = t - T(0.5) * phi_x_t + c * phi.cross(phi_x_t);
  xi.template tail<3>() = phi;
  return xi;
}

class RelativePoseFactor {
 public:
  // sqrt_information: upper-triangular U with U^T U = information. bearing_at_measured_length (ignored when the
  // measured translation is zero): the estimated translation is compared as a length and a bearing, the bearing's
  // error taken at the measured length, so that a step cannot shrink a residual across it by getting shorter
  // (docs/pose_graph.md, "Length and bearing of a step"). To first order the residual is the same.
  RelativePoseFactor(const SE3& T_meas, const Mat6& sqrt_information, bool bearing_at_measured_length = false)
      : q_meas_inv_(T_meas.quat().conjugate()),
        t_meas_(T_meas.translation()),
        sqrt_information_(sqrt_information),
        measured_length_m_(t_meas_.norm()),
        bearing_at_measured_length_(bearing_at_measured_length && measured_length_m_ > 0.0) {}

  // r = U Log(T_meas^-1 (T_W_u^-1 T_W_v)) (paper: both factors measure (L_u)^-1 L_v).
  template <typename T>
  bool operator()(const T* pose_u, const T* pose_v, T* residual) const {
    using Quat_t = Eigen::Quaternion<T>;
    using Vec3_t = Eigen::Matrix<T, 3, 1>;
    const Eigen::Map<const Quat_t> q_W_u(pose_u);
    const Eigen::Map<const Quat_t> q_W_v(pose_v);
    const Eigen::Map<const Vec3_t> t_W_u(pose_u + 4);
    const Eigen::Map<const Vec3_t> t_W_v(pose_v + 4);
    const Quat_t q_u_W = q_W_u.conjugate();
    const Quat_t q_meas_inv = q_meas_inv_.template cast<T>();
    const Quat_t q_err = q_meas_inv * (q_u_W * q_W_v);
    Vec3_t t_u_v = q_u_W * (t_W_v - t_W_u);
    if (bearing_at_measured_length_) {
      // |t_meas| t / |t| + (|t| - |t_meas|) t_meas / |t_meas|: a change of length alone, or of direction alone,
      // gives t itself; the part across t_meas no longer scales with the estimated length |t|.
      using std::sqrt;
      const T length = sqrt(t_u_v.squaredNorm());
      const T measured_m(measured_length_m_);
      t_u_v = t_u_v * (measured_m / length) + (length - measured_m) * (t_meas_ / measured_length_m_).template cast<T>();
    }
    const Vec3_t t_err = q_meas_inv * (t_u_v - t_meas_.template cast<T>());
    Eigen::Map<Eigen::Matrix<T, 6, 1>> r(residual);
    r = sqrt_information_.template cast<T>() * se3_log(q_err, t_err);
    return true;
  }

 private:
  Quat q_meas_inv_;
  Vec3 t_meas_;
  Mat6 sqrt_information_;
  double measured_length_m_;
  bool bearing_at_measured_length_;
};

}  // namespace vilslam::loop
