#include "vio/vision_factor.h"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <algorithm>

namespace vilslam {
namespace {

constexpr double kMinDepth_m = 0.05;
constexpr int kPoseDim = 6;  // [dphi, dp]: the first six tangent coordinates of a state
static_assert(kRot == 0 && kPos == 3, "the vision factor's blocks are the leading rotation and position");

// Camera c's pose in W for a state.
SE3 camera_in_world(const NavState& x, const SE3& T_I_C) { return x.T_W_I() * T_I_C; }

// Point in the camera frame and the 2x3 Jacobian of its perspective projection.
Eigen::Matrix<double, 2, 3> projection_jacobian(const Vec3& p_C) {
  const double iz = 1.0 / p_C.z();
  Eigen::Matrix<double, 2, 3> J;
  J << iz, 0, -p_C.x() * iz * iz, 0, iz, -p_C.y() * iz * iz;
  return J;
}

// Linear least squares on u x (R_C_W x + t_C_W) = 0 for every camera.
std::optional<Vec3> linear_triangulation(const std::vector<StereoObservation>& obs,
                                         const std::vector<NavState>& states, const StereoExtrinsics& extr) {
  Mat3 AtA = Mat3::Zero();
  Vec3 Atb = Vec3::Zero();
  for (const StereoObservation& o : obs) {
    for (int c = 0; c < 2; ++c) {
      const SE3 T_C_W = camera_in_world(states[o.slot], c == 0 ? extr.T_I_C0 : extr.T_I_C1).inverse();
      const Mat3 R = T_C_W.rotation();
      const Vec3& t = T_C_W.translation();
      const Eigen::Vector2d& u = c == 0 ? o.left_norm : o.right_norm;
      for (int k = 0; k < 2; ++k) {
        const Eigen::RowVector3d a = u[k] * R.row(2) - R.row(k);
        const double rhs = t[k] - u[k] * t[2];
        AtA += a.transpose() * a;
        Atb += a.transpose() * rhs;
      }
    }
  }
  Eigen::SelfAdjointEigenSolver<Mat3> eig(AtA);
  if (eig.eigenvalues()(0) < 1e-9 * eig.eigenvalues()(2) || eig.eigenvalues()(2) <= 0) return std::nullopt;
  return Vec3(AtA.ldlt().solve(Atb));
}

}  // namespace

Eigen::VectorXd LandmarkLinearization::stacked_b() const {
  Eigen::VectorXd b(4 * blocks.size());
  for (size_t k = 0; k < blocks.size(); ++k) b.segment<4>(4 * k) = blocks[k].b;
  return b;
}

Eigen::MatrixXd LandmarkLinearization::stacked_F() const {
  Eigen::MatrixXd F = Eigen::MatrixXd::Zero(4 * blocks.size(), kPoseDim * blocks.size());
  for (size_t k = 0; k < blocks.size(); ++k) F.block<4, kPoseDim>(4 * k, kPoseDim * k) = blocks[k].F;
  return F;
}

Eigen::MatrixXd LandmarkLinearization::stacked_E() const {
  Eigen::MatrixXd E(4 * blocks.size(), 3);
  for (size_t k = 0; k < blocks.size(); ++k) E.block<4, 3>(4 * k, 0) = blocks[k].E;
  return E;
}

LandmarkLinearization linearize_landmark(const std::vector<StereoObservation>& obs,
                                         const std::vector<NavState>& states, const StereoExtrinsics& extr,
                                         const Vec3& x_W, double sigma_norm) {
  const SE3 T_C_I[2] = {extr.T_I_C0.inverse(), extr.T_I_C1.inverse()};
  LandmarkLinearization lin;
  lin.blocks.resize(obs.size());
  for (size_t k = 0; k < obs.size(); ++k) {
    const NavState& x = states[obs[k].slot];
    const Mat3 Rt = x.R_W_I.transpose();
    const Vec3 p_I = Rt * (x_W - x.p_W_I);
    const Mat3 hat_p_I = so3::hat(p_I);
    ObservationLinearization& block = lin.blocks[k];
    for (int c = 0; c < 2; ++c) {
      const Mat3 R_C_I = T_C_I[c].rotation();
      const Vec3 p_C = T_C_I[c] * p_I;
      const Eigen::Vector2d& z = c == 0 ? obs[k].left_norm : obs[k].right_norm;
      // paper eq. (1): r = z - h(xi, x_p), h the perspective projection in normalized coordinates.
      block.b.segment<2>(2 * c) = (z - p_C.head<2>() / p_C.z()) / sigma_norm;
      const Eigen::Matrix<double, 2, 3> dr_dpI = -projection_jacobian(p_C) * R_C_I / sigma_norm;
      // p_I = R^T (x_W - p): d/dphi = [p_I]x, d/dp = -R^T, d/dx_W = R^T.
      block.F.block<2, 3>(2 * c, kRot) = dr_dpI * hat_p_I;
      block.E.block<2, 3>(2 * c, 0) = dr_dpI * Rt;
      block.F.block<2, 3>(2 * c, kPos) = -block.E.block<2, 3>(2 * c, 0);
    }
  }
  return lin;
}

std::optional<Vec3> triangulate(const std::vector<StereoObservation>& obs, const std::vector<NavState>& states,
                                const StereoExtrinsics& extr) {
  std::optional<Vec3> x_W = linear_triangulation(obs, states, extr);
  if (!x_W) return std::nullopt;
  for (int it = 0; it < 3; ++it) {
    const LandmarkLinearization lin = linearize_landmark(obs, states, extr, *x_W, 1.0);
    Mat3 EtE = Mat3::Zero();
    Vec3 Etb = Vec3::Zero();
    for (const ObservationLinearization& o : lin.blocks) {
      EtE += o.E.transpose() * o.E;
      Etb += o.E.transpose() * o.b;
    }
    *x_W -= EtE.ldlt().solve(Etb);
  }
  for (const StereoObservation& o : obs) {
    for (const SE3* T_I_C : {&extr.T_I_C0, &extr.T_I_C1}) {
      if ((camera_in_world(states[o.slot], *T_I_C).inverse() * *x_W).z() < kMinDepth_m) return std::nullopt;
    }
  }
  if (!x_W->allFinite()) return std::nullopt;
  return x_W;
}

LinearFactor structureless_factor(const std::vector<StereoObservation>& obs, const LandmarkLinearization& lin) {
  // With Q = I - E (E^T E)^-1 E^T symmetric and idempotent: (QF)^T (QF) = F^T F - F^T E (E^T E)^-1 E^T F,
  // (QF)^T (Qb) = F^T b - F^T E (E^T E)^-1 E^T b, ||Qb||^2 = b^T b - b^T E (E^T E)^-1 E^T b; F is block
  // diagonal, so F^T F is too and F^T E stacks the per-observation F_k^T E_k.
  const int m = static_cast<int>(obs.size());
  Mat3 EtE = Mat3::Zero();
  Vec3 Etb = Vec3::Zero();
  double btb = 0;
  std::vector<Eigen::Matrix<double, kPoseDim, 3>> FtE(m);
  for (int k = 0; k < m; ++k) {
    const ObservationLinearization& o = lin.blocks[k];
    EtE += o.E.transpose() * o.E;
    Etb += o.E.transpose() * o.b;
    btb += o.b.squaredNorm();
    FtE[k] = o.F.transpose() * o.E;
  }
  const Eigen::LDLT<Mat3> EtE_ldlt(EtE);
  const Mat3 EtE_inv = EtE_ldlt.solve(Mat3::Identity());
  const Vec3 EtE_inv_Etb = EtE_ldlt.solve(Etb);
  LinearFactor f;
  f.block_dim = kPoseDim;
  for (const StereoObservation& o : obs) f.slots.push_back(o.slot);
  f.H.resize(kPoseDim * m, kPoseDim * m);
  f.g.resize(kPoseDim * m);
  for (int k = 0; k < m; ++k) {
    const ObservationLinearization& o = lin.blocks[k];
    const Eigen::Matrix<double, kPoseDim, 3> FtE_EtE_inv = FtE[k] * EtE_inv;
    for (int l = 0; l < m; ++l) f.H.block<kPoseDim, kPoseDim>(kPoseDim * k, kPoseDim * l) = -FtE_EtE_inv * FtE[l].transpose();
    f.H.block<kPoseDim, kPoseDim>(kPoseDim * k, kPoseDim * k) += o.F.transpose() * o.F;
    f.g.segment<kPoseDim>(kPoseDim * k) = o.F.transpose() * o.b - FtE[k] * EtE_inv_Etb;
  }
  f.cost = std::max(0.0, btb - Etb.dot(EtE_inv_Etb));
  return f;
}

}  // namespace vilslam
