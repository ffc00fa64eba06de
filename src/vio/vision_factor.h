#pragma once
// The structureless vision factor of the paper (Sec. "Structureless vision factor"): the stacked
// reprojection residuals of one landmark in the left and right images of the window states that see it,
// linearized at a landmark triangulated from the window and projected onto the null space of E_p.
#include <Eigen/Core>
#include <optional>
#include <vector>

#include "common/lie.h"
#include "vio/dense_lm.h"
#include "vio/window_state.h"

namespace vilslam {

struct StereoObservation {
  int slot = 0;             // window position of the observing state
  Eigen::Vector2d left_norm;   // normalized coordinates in C0
  Eigen::Vector2d right_norm;  // normalized coordinates in C1
};

struct StereoExtrinsics {
  SE3 T_I_C0;
  SE3 T_I_C1;
};

// Linearization of ||F_p dxi + E_p dx_p + b_p||^2 (paper eq. (2)-(3)), whitened by sigma_norm: four rows
// per observation (left x, y, right x, y), F_p with one 6-column block [dphi, dp] per observation (the
// vision residual does not depend on velocity or biases). F_p is block diagonal, so it is kept per
// observation: block k holds rows 4k..4k+3 of b_p, E_p and the k-th diagonal block of F_p.
struct ObservationLinearization {
  Eigen::Matrix<double, 4, 1> b;  // z - h(xi, x_p) / sigma
  Eigen::Matrix<double, 4, 6> F;  // d b / d [dphi, dp] of the observing state
  Eigen::Matrix<double, 4, 3> E;  // d b / d x_p
};

struct LandmarkLinearization {
  std::vector<ObservationLinearization> blocks;  // in the order of the observations

  // The stacked forms of the paper's eq. (2): b_p (4m), F_p (4m x 6m, block diagonal), E_p (4m x 3).
  Eigen::VectorXd stacked_b() const;
  Eigen::MatrixXd stacked_F() const;
  Eigen::MatrixXd stacked_E() const;
};

// Landmark in W from all observations: linear triangulation refined by Gauss-Newton on the reprojection
// error. nullopt when it is ill-conditioned or behind a camera.
std::optional<Vec3> triangulate(const std::vector<StereoObservation>& obs, const std::vector<NavState>& states,
                                const StereoExtrinsics& extr);

LandmarkLinearization linearize_landmark(const std::vector<StereoObservation>& obs,
                                         const std::vector<NavState>& states, const StereoExtrinsics& extr,
                                         const Vec3& x_W, double sigma_norm);

// Normal-equation contribution of Q_p F_p and Q_p b_p, Q_p = I - E_p (E_p^T E_p)^-1 E_p^T (paper eq. (4)).
LinearFactor structureless_factor(const std::vector<StereoObservation>& obs, const LandmarkLinearization& lin);

}  // namespace vilslam
