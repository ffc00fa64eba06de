#include "vio/imu_factor.h"

namespace vilslam {

ImuResidual imu_residual(const Preintegration& preint, const NavState& x_i, const NavState& x_j,
                         const Vec3& gravity_W) {
  const double dt = preint.dt_s();
  const Mat3 Rt_i = x_i.R_W_I.transpose();
  const Vec3 dbg = x_i.bias_gyro_rad_s - preint.bias_gyro_lin();
  const Vec3& bg = x_i.bias_gyro_rad_s;
  const Vec3& ba = x_i.bias_accel_m_s2;

  // eq. (45): residuals with the first-order bias-corrected deltas of eq. (44).
  const Mat3 dR_corr = preint.corrected_delta_R(bg);
  const Vec3 r_R = so3::log(Mat3(dR_corr.transpose() * Rt_i * x_j.R_W_I));
  const Vec3 dv_W = x_j.v_W_m_s - x_i.v_W_m_s - gravity_W * dt;
  const Vec3 dp_W = x_j.p_W_I - x_i.p_W_I - x_i.v_W_m_s * dt - 0.5 * gravity_W * dt * dt;
  const Vec3 v_I = Rt_i * dv_W;
  const Vec3 p_I = Rt_i * dp_W;

  ImuResidual out;
  out.r << r_R, v_I - preint.corrected_delta_v(bg, ba), p_I - preint.corrected_delta_p(bg, ba);
  out.J_i.setZero();
  out.J_j.setZero();

  // Appendix C, with the world-frame position increment p <- p + dp.
  const Mat3 Jr_inv = so3::right_jacobian_inv(r_R);
  out.J_i.block<3, 3>(0, kRot) = -Jr_inv * x_j.R_W_I.transpose() * x_i.R_W_I;
  out.J_j.block<3, 3>(0, kRot) = Jr_inv;
  out.J_i.block<3, 3>(0, kBiasGyro) =
      -Jr_inv * so3::exp(r_R).transpose() * so3::right_jacobian(preint.dR_dbg() * dbg) * preint.dR_dbg();

  out.J_i.block<3, 3>(3, kRot) = so3::hat(v_I);
  out.J_i.block<3, 3>(3, kVel) = -Rt_i;
  out.J_j.block<3, 3>(3, kVel) = Rt_i;
  out.J_i.block<3, 3>(3, kBiasGyro) = -preint.dv_dbg();
  out.J_i.block<3, 3>(3, kBiasAccel) = -preint.dv_dba();

  out.J_i.block<3, 3>(6, kRot) = so3::hat(p_I);
  out.J_i.block<3, 3>(6, kPos) = -Rt_i;
  out.J_j.block<3, 3>(6, kPos) = Rt_i;
  out.J_i.block<3, 3>(6, kVel) = -Rt_i * dt;
  out.J_i.block<3, 3>(6, kBiasGyro) = -preint.dp_dbg();
  out.J_i.block<3, 3>(6, kBiasAccel) = -preint.dp_dba();
  return out;
}

BiasResidual bias_residual(const NavState& x_i, const NavState& x_j) {
  BiasResidual out;
  out.r << x_j.bias_gyro_rad_s - x_i.bias_gyro_rad_s, x_j.bias_accel_m_s2 - x_i.bias_accel_m_s2;
  out.J_i.setZero();
  out.J_j.setZero();
  out.J_i.block<6, 6>(0, kBiasGyro) = -Eigen::Matrix<double, 6, 6>::Identity();
  out.J_j.block<6, 6>(0, kBiasGyro) = Eigen::Matrix<double, 6, 6>::Identity();
  return out;
}

Eigen::Matrix<double, 6, 6> bias_covariance(const ImuNoise& noise, double dt_s) {
  Eigen::Matrix<double, 6, 1> d;
  d << Vec3::Constant(noise.gyro_random_walk * noise.gyro_random_walk * dt_s),
      Vec3::Constant(noise.accel_random_walk * noise.accel_random_walk * dt_s);
  return d.asDiagonal();
}

NavState predict_state(const Preintegration& preint, const NavState& x_i, const Vec3& gravity_W) {
  const double dt = preint.dt_s();
  const Vec3& bg = x_i.bias_gyro_rad_s;
  const Vec3& ba = x_i.bias_accel_m_s2;
  NavState x_j = x_i;
  x_j.t_ns = x_i.t_ns + s_to_ns(dt);
  // eq. (44) solved for the state at j.
  x_j.R_W_I = so3::project(x_i.R_W_I * preint.corrected_delta_R(bg));
  x_j.v_W_m_s = x_i.v_W_m_s + gravity_W * dt + x_i.R_W_I * preint.corrected_delta_v(bg, ba);
  x_j.p_W_I = x_i.p_W_I + x_i.v_W_m_s * dt + 0.5 * gravity_W * dt * dt + x_i.R_W_I * preint.corrected_delta_p(bg, ba);
  return x_j;
}

}  // namespace vilslam
