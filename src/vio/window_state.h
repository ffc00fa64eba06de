#pragma once
// The VIO state S_t of the paper (Sec. "Stereo visual inertial odometry"): IMU pose, velocity and biases
// at a stereo frame time, and its 15-dimensional tangent space used by every factor and the solver.
#include <Eigen/Core>

#include "common/lie.h"
#include "common/time.h"

namespace vilslam {

constexpr int kStateDim = 15;
// Tangent ordering of a state perturbation dx: R_W_I <- R_W_I Exp(dphi), p_W_I <- p_W_I + dp (world frame),
// v_W <- v_W + dv, biases additive.
constexpr int kRot = 0, kPos = 3, kVel = 6, kBiasGyro = 9, kBiasAccel = 12;

using Vec15 = Eigen::Matrix<double, kStateDim, 1>;
using Mat15 = Eigen::Matrix<double, kStateDim, kStateDim>;

struct NavState {
  TimeNs t_ns = 0;
  Mat3 R_W_I = Mat3::Identity();
  Vec3 p_W_I = Vec3::Zero();
  Vec3 v_W_m_s = Vec3::Zero();
  Vec3 bias_gyro_rad_s = Vec3::Zero();
  Vec3 bias_accel_m_s2 = Vec3::Zero();

  SE3 T_W_I() const { return SE3(R_W_I, p_W_I); }
};

// x [+] dx.
NavState boxplus(const NavState& x, const Vec15& dx);
// x [-] x_lin, the perturbation dx with x_lin [+] dx = x.
Vec15 boxminus(const NavState& x, const NavState& x_lin);
// d(x [-] x_lin)/d(dx) at x (identity except Jr^-1 of the rotation difference, Forster eq. (9)).
Mat15 boxminus_jacobian(const NavState& x, const NavState& x_lin);

// The standard deviation of x's tilt (its roll and pitch against gravity; the larger of the two), rad, from a
// covariance in the tangent ordering above. The up direction in I, u = R_W_I^T e_z, moves by -hat(u) dphi, which
// leaves out the yaw (dphi along u), the direction a VIO cannot observe and whose variance is not to be trusted.
// 0 when the covariance gives no finite value.
double tilt_sigma_rad(const NavState& x, const Mat15& covariance);

}  // namespace vilslam
