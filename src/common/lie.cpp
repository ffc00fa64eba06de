#include "common/lie.h"

#include <Eigen/SVD>
#include <cmath>

namespace vilslam {
namespace so3 {
namespace {
constexpr double kSmallAngle = 1e-8;
}

Mat3 hat(const Vec3& w) {
  Mat3 W;
  W << 0, -w.z(), w.y(), w.z(), 0, -w.x(), -w.y(), w.x(), 0;
  return W;
}

Vec3 vee(const Mat3& W) { return Vec3(W(2, 1), W(0, 2), W(1, 0)); }

Quat exp_quat(const Vec3& phi) {
  const double theta = phi.norm();
  if (theta < kSmallAngle) {
    return Quat(1.0, 0.5 * phi.x(), 0.5 * phi.y(), 0.5 * phi.z()).normalized();
  }
  const Vec3 axis = phi / theta;
  const double s = std::sin(0.5 * theta);
  return Quat(std::cos(0.5 * theta), s * axis.x(), s * axis.y(), s * axis.z());
}

Mat3 exp(const Vec3& phi) { return exp_quat(phi).toRotationMatrix(); }

Vec3 log(const Quat& q_in) {
  Quat q = q_in.normalized();
  if (q.w() < 0) q.coeffs() *= -1.0;  // shortest rotation
  const Vec3 v = q.vec();
  const double s = v.norm();
  if (s < kSmallAngle) return 2.0 * v / q.w();
  const double theta = 2.0 * std::atan2(s, q.w());
  return theta * v / s;
}

Vec3 log(const Mat3& R) { return log(Quat(R)); }

// Forster et al. eq. (8).
Mat3 right_jacobian(const Vec3& phi) {
  const double theta = phi.norm();
  const Mat3 W = hat(phi);
  if (theta < 1e-5) return Mat3::Identity() - 0.5 * W + W * W / 6.0;
  const double t2 = theta * theta;
  return Mat3::Identity() - (1.0 - std::cos(theta)) / t2 * W + (theta - std::sin(theta)) / (t2 * theta) * W * W;
}

// Forster et al. eq. (9).
Mat3 right_jacobian_inv(const Vec3& phi) {
  const double theta = phi.norm();
  const Mat3 W = hat(phi);
  if (theta < 1e-5) return Mat3::Identity() + 0.5 * W + W * W / 12.0;
  const double t2 = theta * theta;
  return Mat3::Identity() + 0.5 * W +
         (1.0 / t2 - (1.0 + std::cos(theta)) / (2.0 * theta * std::sin(theta))) * W * W;
}

Mat3 left_jacobian(const Vec3& phi) { return right_jacobian(-phi); }
Mat3 left_jacobian_inv(const Vec3& phi) { return right_jacobian_inv(-phi); }

Mat3 project(const Mat3& M) {
  Eigen::JacobiSVD<Mat3> svd(M, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Mat3 R = svd.matrixU() * svd.matrixV().transpose();
  if (R.determinant() < 0) {
    Mat3 U = svd.matrixU();
    U.col(2) *= -1.0;
    R = U * svd.matrixV().transpose();
  }
  return R;
}

double orthonormality_error(const Mat3& R) {
  const double ortho = (R.transpose() * R - Mat3::Identity()).cwiseAbs().maxCoeff();
  return std::max(ortho, std::abs(R.determinant() - 1.0));
}

double yaw_rad(const Mat3& R) { return std::atan2(R(1, 0), R(0, 0)); }

Mat3 rot_z(double yaw) { return Eigen::AngleAxisd(yaw, Vec3::UnitZ()).toRotationMatrix(); }

}  // namespace so3

// Exp of se(3): t = Jl(phi) rho (Barfoot, State Estimation for Robotics, eq. 7.85).
SE3 SE3::exp(const Vec6& xi) {
  const Vec3 rho = xi.head<3>();
  const Vec3 phi = xi.tail<3>();
  return SE3(so3::exp_quat(phi), so3::left_jacobian(phi) * rho);
}

Vec6 SE3::log() const {
  const Vec3 phi = so3::log(q_);
  Vec6 xi;
  xi << so3::left_jacobian_inv(phi) * t_, phi;
  return xi;
}

Mat4 SE3::matrix() const {
  Mat4 T = Mat4::Identity();
  T.topLeftCorner<3, 3>() = rotation();
  T.topRightCorner<3, 1>() = t_;
  return T;
}

Mat6 SE3::adjoint() const {
  const Mat3 R = rotation();
  Mat6 A = Mat6::Zero();
  A.topLeftCorner<3, 3>() = R;
  A.topRightCorner<3, 3>() = so3::hat(t_) * R;
  A.bottomRightCorner<3, 3>() = R;
  return A;
}

SE3 interpolate(const SE3& a, const SE3& b, double alpha) {
  return SE3(a.quat().slerp(alpha, b.quat()), (1.0 - alpha) * a.translation() + alpha * b.translation());
}

}  // namespace vilslam
