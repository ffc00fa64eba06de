// The relative-pose factor: its residual equals the SE3::log of common/lie.h, and its autodiff Jacobians on
// the pose manifold match central differences.
#include <gtest/gtest.h>

#include <ceres/autodiff_cost_function.h>
#include <ceres/product_manifold.h>

#include <array>
#include <cmath>
#include <utility>

#include "loop/relative_pose_factor.h"

namespace vilslam {
namespace {

using PoseManifold = ceres::ProductManifold<ceres::EigenQuaternionManifold, ceres::EuclideanManifold<3>>;
using Block = std::array<double, loop::kPoseBlockSize>;
using Jacobian = Eigen::Matrix<double, 6, loop::kPoseBlockSize, Eigen::RowMajor>;

Block block_of(const SE3& T) {
  return {T.quat().x(), T.quat().y(), T.quat().z(), T.quat().w(),
          T.translation().x(), T.translation().y(), T.translation().z()};
}

SE3 pose(double rx, double ry, double rz, double tx, double ty, double tz) {
  Vec6 xi;
  xi << tx, ty, tz, rx, ry, rz;
  return SE3::exp(xi);
}

Mat6 sqrt_info() {
  Mat6 U = Mat6::Zero();
  U.diagonal() << 50, 40, 30, 500, 400, 300;
  U(0, 4) = 7.0;  // a correlated, non-diagonal square root
  return U;
}

struct Case {
  SE3 T_W_u, T_W_v, T_meas;
};

// Error rotation far from 0 (2.6 rad), moderate, and nearly 0 (the series branch of se3_log).
std::array<Case, 3> cases() {
  const SE3 T_W_u = pose(0.3, -0.2, 1.1, 1.0, 2.0, 0.5);
  const SE3 T_W_v = pose(-0.4, 0.1, 2.0, 3.0, -1.0, 0.2);
  const SE3 T_u_v = T_W_u.inverse() * T_W_v;
  return {Case{T_W_u, T_W_v, T_u_v * pose(2.0, -1.5, 0.8, 0.3, 0.1, -0.2)},
          Case{T_W_u, T_W_v, T_u_v * pose(0.1, 0.05, -0.2, 0.3, 0.1, -0.2)},
          Case{T_W_u, T_W_v, T_u_v * pose(1e-7, -2e-7, 1e-7, 0.3, 0.1, -0.2)}};
}

// Length and bearing apart (docs/pose_graph.md, "Length and bearing of a step"): a step measured 1 m along x. An
// estimate only longer, or only turned, gives the plain residual; one both shorter and turned keeps the turn's part
// across the step at the measured length, where the plain residual shrinks it with the estimated length.
TEST(RelativePoseFactor, BearingAtTheMeasuredLengthDoesNotShrinkWithTheStep) {
  const SE3 T_meas(Quat::Identity(), Vec3(1.0, 0.0, 0.0));
  const Block u = block_of(SE3());
  const Mat6 I = Mat6::Identity();
  const auto residuals = [&](const Vec3& t_u_v) {
    const Block v = block_of(SE3(Quat::Identity(), t_u_v));
    Vec6 plain, apart;
    loop::RelativePoseFactor(T_meas, I)(u.data(), v.data(), plain.data());
    loop::RelativePoseFactor(T_meas, I, true)(u.data(), v.data(), apart.data());
    return std::make_pair(plain, apart);
  };
  const double angle = 0.01;
  for (const Vec3& t : {Vec3(1.2, 0.0, 0.0), Vec3(std::cos(angle), 0.0, std::sin(angle))}) {
    const auto [plain, apart] = residuals(t);
    EXPECT_LT((plain - apart).norm(), 1e-12) << t.transpose();
  }
  const auto [plain, apart] = residuals(0.5 * Vec3(std::cos(angle), 0.0, std::sin(angle)));
  EXPECT_NEAR(plain(2), 0.5 * std::sin(angle), 1e-12);
  EXPECT_NEAR(apart(2), std::sin(angle), 1e-12);
  EXPECT_NEAR(apart(0), plain(0), 1e-3);  // the length's part: 0.5 cos(angle) - 1 against 0.5 - 1
}

TEST(RelativePoseFactor, ResidualIsSe3Log) {
  for (const Case& c : cases()) {
    const Block u = block_of(c.T_W_u), v = block_of(c.T_W_v);
    Vec6 r;
    loop::RelativePoseFactor(c.T_meas, sqrt_info())(u.data(), v.data(), r.data());
    const Vec6 expected = sqrt_info() * (c.T_meas.inverse() * (c.T_W_u.inverse() * c.T_W_v)).log();
    EXPECT_LT((r - expected).norm(), 1e-9 * (1.0 + expected.norm())) << r.transpose() << " vs " << expected.transpose();
  }
}

TEST(RelativePoseFactor, AutodiffJacobiansMatchNumericOnManifold) {
  const PoseManifold manifold;
  for (const Case& c : cases()) {
    const ceres::AutoDiffCostFunction<loop::RelativePoseFactor, 6, 7, 7> cost(
        new loop::RelativePoseFactor(c.T_meas, sqrt_info()));
    std::array<Block, 2> blocks = {block_of(c.T_W_u), block_of(c.T_W_v)};
    const double* params[2] = {blocks[0].data(), blocks[1].data()};
    Jacobian J_ambient[2];
    double* jacobians[2] = {J_ambient[0].data(), J_ambient[1].data()};
    Vec6 r;
    ASSERT_TRUE(cost.Evaluate(params, r.data(), jacobians));

    for (int b = 0; b < 2; ++b) {
      Eigen::Matrix<double, 7, 6, Eigen::RowMajor> plus_jacobian;
      ASSERT_TRUE(manifold.PlusJacobian(blocks[b].data(), plus_jacobian.data()));
      const Mat6 J_analytic = J_ambient[b] * plus_jacobian;
      Mat6 J_numeric;
      constexpr double kStep = 1e-6;
      for (int k = 0; k < 6; ++k) {
        Vec6 delta = Vec6::Zero();
        Vec6 r_plus, r_minus;
        for (const double sign : {1.0, -1.0}) {
          delta[k] = sign * kStep;
          Block perturbed;
          ASSERT_TRUE(manifold.Plus(blocks[b].data(), delta.data(), perturbed.data()));
          std::array<Block, 2> p = blocks;
          p[b] = perturbed;
          const double* pp[2] = {p[0].data(), p[1].data()};
          ASSERT_TRUE(cost.Evaluate(pp, (sign > 0 ? r_plus : r_minus).data(), nullptr));
        }
        J_numeric.col(k) = (r_plus - r_minus) / (2.0 * kStep);
      }
      EXPECT_LT((J_analytic - J_numeric).norm(), 1e-5 * J_numeric.norm()) << "block " << b << "\n"
                                                                            << J_analytic << "\nvs\n"
                                                                            << J_numeric;
    }
  }
}

}  // namespace
}  // namespace vilslam
