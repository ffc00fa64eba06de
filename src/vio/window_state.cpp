#include "vio/window_state.h"

#include <Eigen/Eigenvalues>
#include <cmath>

namespace vilslam {

NavState boxplus(const NavState& x, const Vec15& dx) {
  NavState y = x;
  y.R_W_I = so3::project(x.R_W_I * so3::exp(dx.segment<3>(kRot)));
  y.p_W_I += dx.segment<3>(kPos);
  y.v_W_m_s += dx.segment<3>(kVel);
  y.bias_gyro_rad_s += dx.segment<3>(kBiasGyro);
  y.bias_accel_m_s2 += dx.segment<3>(kBiasAccel);
  return y;
}

Vec15 boxminus(const NavState& x, const NavState& x_lin) {
  Vec15 d;
  d.segment<3>(kRot) = so3::log(Mat3(x_lin.R_W_I.transpose() * x.R_W_I));
  d.segment<3>(kPos) = x.p_W_I - x_lin.p_W_I;
  d.segment<3>(kVel) = x.v_W_m_s - x_lin.v_W_m_s;
  d.segment<3>(kBiasGyro) = x.bias_gyro_rad_s - x_lin.bias_gyro_rad_s;
  d.segment<3>(kBiasAccel) = x.bias_accel_m_s2 - x_lin.bias_accel_m_s2;
  return d;
}

Mat15 boxminus_jacobian(const NavState& x, const NavState& x_lin) {
  Mat15 J = Mat15::Identity();
  J.block<3, 3>(kRot, kRot) = so3::right_jacobian_inv(so3::log(Mat3(x_lin.R_W_I.transpose() * x.R_W_I)));
  return J;
}

double tilt_sigma_rad(const NavState& x, const Mat15& covariance) {
  const Mat3 J = so3::hat(x.R_W_I.transpose() * Vec3::UnitZ());
  const Mat3 up_covariance = J * covariance.block<3, 3>(kRot, kRot) * J.transpose();
  if (!up_covariance.allFinite()) return 0.0;
  const double largest = Eigen::SelfAdjointEigenSolver<Mat3>(up_covariance, Eigen::EigenvaluesOnly).eigenvalues()(2);
  return largest > 0.0 ? std::sqrt(largest) : 0.0;
}

}  // namespace vilslam
