#pragma once
// The IMU pre-integration factor r^I_ij of the paper: preintegrated rotation, velocity and position
// residuals (Forster et al. 2017, eq. (45)) and the bias random-walk residual between consecutive states.
#include <Eigen/Core>

#include "vio/preintegration.h"
#include "vio/window_state.h"

namespace vilslam {

using Mat9x15 = Eigen::Matrix<double, 9, kStateDim>;
using Mat6x15 = Eigen::Matrix<double, 6, kStateDim>;
using Vec9 = Eigen::Matrix<double, 9, 1>;

struct ImuResidual {
  Vec9 r;      // [r_R; r_v; r_p], not whitened
  Mat9x15 J_i;  // d r / d dx_i
  Mat9x15 J_j;  // d r / d dx_j
};

struct BiasResidual {
  Eigen::Matrix<double, 6, 1> r;  // [bg_j - bg_i; ba_j - ba_i]
  Mat6x15 J_i;
  Mat6x15 J_j;
};

// Residual and analytic Jacobians of the preintegrated measurement between x_i and x_j (eq. (45), App. C).
// The biases of x_i correct the deltas to first order (eq. (44)); gravity_W is the gravity vector.
ImuResidual imu_residual(const Preintegration& preint, const NavState& x_i, const NavState& x_j,
                         const Vec3& gravity_W);

// Bias random walk between consecutive states (Forster eq. (48)).
BiasResidual bias_residual(const NavState& x_i, const NavState& x_j);
// Its covariance over dt_s: diag(sigma_bg^2 dt, sigma_ba^2 dt) from the random-walk densities.
Eigen::Matrix<double, 6, 6> bias_covariance(const ImuNoise& noise, double dt_s);

// State x_j predicted from x_i by the preintegrated measurement with x_i's biases (eq. (44) with r = 0).
NavState predict_state(const Preintegration& preint, const NavState& x_i, const Vec3& gravity_W);

}  // namespace vilslam
