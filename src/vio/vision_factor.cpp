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

LandmarkLinearization linearize_landmark(const std::vector<StereoObservation>& obs,
                                         const std::vector<NavState>& states, const StereoExtrinsics& extr,
                                         const Vec3& x_W, double sigma_norm) {
  const int m = static_cast<int>(obs.size());
  LandmarkLinearization lin;
  lin.b.resize(4 * m);
  lin.F.setZero(4 * m, kPoseDim * m);
  lin.E.resize(4 * m, 3);
  for (int k = 0; k < m; ++k) {
    const NavState& x = states[obs[k].slot];
    const Mat3 Rt = x.R_W_I.transpose();
    const Vec3 p_I = Rt * (x_W - x.p_W_I);
    for (int c = 0; c < 2; ++c) {
      const SE3 T_C_I = (c == 0 ? extr.T_I_C0 : extr.T_I_C1).inverse();
      const Mat3 R_C_I = T_C_I.rotation();
      const Vec3 p_C = T_C_I * p_I;
      const Eigen::Vector2d& z = c == 0 ? obs[k].left_norm : obs[k].right_norm;
      const int row = 4 * k + 2 * c;
      // paper eq. (1): r = z - h(xi, x_p), h the perspective projection in normalized coordinates.
      lin.b.segment<2>(row) = (z - p_C.head<2>() / p_C.z()) / sigma_norm;
      const Eigen::Matrix<double, 2, 3> dr_dpC = -projection_jacobian(p_C) / sigma_norm;
      // p_I = R^T (x_W - p): d/dphi = [p_I]x, d/dp = -R^T, d/dx_W = R^T.
      lin.F.block<2, 3>(row, kPoseDim * k + kRot) = dr_dpC * R_C_I * so3::hat(p_I);
      lin.F.block<2, 3>(row, kPoseDim * k + kPos) = -dr_dpC * R_C_I * Rt;
      lin.E.block<2, 3>(row, 0) = dr_dpC * R_C_I * Rt;
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
    const Mat3 EtE = lin.E.transpose() * lin.E;
    *x_W -= EtE.ldlt().solve(lin.E.transpose() * lin.b);
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
  // (QF)^T (Qb) = F^T b - F^T E (E^T E)^-1 E^T b, ||Qb||^2 = b^T b - b^T E (E^T E)^-1 E^T b.
  const Eigen::LDLT<Mat3> EtE(lin.E.transpose() * lin.E);
  const Eigen::MatrixXd FtE = lin.F.transpose() * lin.E;
  const Vec3 Etb = lin.E.transpose() * lin.b;
  LinearFactor f;
  f.block_dim = kPoseDim;
  for (const StereoObservation& o : obs) f.slots.push_back(o.slot);
  f.H = -FtE * EtE.solve(FtE.transpose());
  for (int k = 0; k < static_cast<int>(obs.size()); ++k) {  // F^T F is block diagonal: one state per row block
    const auto F_k = lin.F.block<4, kPoseDim>(4 * k, kPoseDim * k);
    f.H.block<kPoseDim, kPoseDim>(kPoseDim * k, kPoseDim * k) += F_k.transpose() * F_k;
  }
  f.g = lin.F.transpose() * lin.b - FtE * EtE.solve(Etb);
  f.cost = std::max(0.0, lin.b.squaredNorm() - Etb.dot(EtE.solve(Etb)));
  return f;
}

}  // namespace vilslam
