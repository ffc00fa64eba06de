#pragma once
// SO(3) and SE(3) on Eigen. Tangent vectors of SE(3) are ordered [rho (translation); phi (rotation)].
// Jacobian conventions follow Forster et al., "On-Manifold Preintegration" (2017), eqs. (8)-(9):
//   Exp(phi + dphi) ~= Exp(phi) Exp(Jr(phi) dphi),  Log(Exp(phi) Exp(dphi)) ~= phi + Jr^-1(phi) dphi.
#include <Eigen/Core>
#include <Eigen/Geometry>

namespace vilslam {

using Vec3 = Eigen::Vector3d;
using Vec6 = Eigen::Matrix<double, 6, 1>;
using Mat3 = Eigen::Matrix3d;
using Mat4 = Eigen::Matrix4d;
using Mat6 = Eigen::Matrix<double, 6, 6>;
using Quat = Eigen::Quaterniond;

namespace so3 {

Mat3 hat(const Vec3& w);
Vec3 vee(const Mat3& W);
Mat3 exp(const Vec3& phi);
Quat exp_quat(const Vec3& phi);
Vec3 log(const Mat3& R);
Vec3 log(const Quat& q);
Mat3 right_jacobian(const Vec3& phi);
Mat3 right_jacobian_inv(const Vec3& phi);
Mat3 left_jacobian(const Vec3& phi);
Mat3 left_jacobian_inv(const Vec3& phi);
// Nearest rotation matrix (SVD projection), for re-orthonormalizing accumulated products.
Mat3 project(const Mat3& M);
// Largest deviation of R^T R from identity and |det R - 1|: 0 for a rotation.
double orthonormality_error(const Mat3& R);
// Heading: the angle about z in R's ZYX (yaw, pitch, roll) decomposition, the one gauge a gravity-aligned frame
// leaves free besides position.
double yaw_rad(const Mat3& R);
// The rotation by yaw about z.
Mat3 rot_z(double yaw);

}  // namespace so3

class SE3 {
 public:
  SE3() : q_(Quat::Identity()), t_(Vec3::Zero()) {}
  SE3(const Quat& q, const Vec3& t) : q_(q.normalized()), t_(t) {}
  SE3(const Mat3& R, const Vec3& t) : q_(Quat(R).normalized()), t_(t) {}
  explicit SE3(const Mat4& T) : SE3(Mat3(T.topLeftCorner<3, 3>()), Vec3(T.topRightCorner<3, 1>())) {}

  static SE3 identity() { return SE3(); }
  static SE3 exp(const Vec6& xi);
  Vec6 log() const;

  const Quat& quat() const { return q_; }
  Mat3 rotation() const { return q_.toRotationMatrix(); }
  const Vec3& translation() const { return t_; }
  Vec3& translation() { return t_; }
  Mat4 matrix() const;

  SE3 inverse() const { return SE3(q_.conjugate(), -(q_.conjugate() * t_)); }
  SE3 operator*(const SE3& o) const { return SE3(q_ * o.q_, t_ + q_ * o.t_); }
  Vec3 operator*(const Vec3& p) const { return q_ * p + t_; }

  // Adjoint: T Exp(xi) T^-1 = Exp(Ad_T xi), with xi = [rho; phi].
  Mat6 adjoint() const;

 private:
  Quat q_;
  Vec3 t_;
};

// Pose at fraction alpha in [0,1] between a and b: slerp on rotation, linear on translation
// (the usual interpolation of timestamped poses; it is not the SE(3) geodesic).
SE3 interpolate(const SE3& a, const SE3& b, double alpha);

}  // namespace vilslam
