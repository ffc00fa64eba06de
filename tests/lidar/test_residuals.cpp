#include <gtest/gtest.h>

#include <random>

#include "lidar/residuals.h"

namespace vilslam::lidar {
namespace {

Vec6 random_vec6(std::mt19937& rng, double scale) {
  std::normal_distribution<double> n(0.0, scale);
  Vec6 v;
  for (int i = 0; i < 6; ++i) v(i) = n(rng);
  return v;
}

// Central differences of f(T Exp(delta)) at delta = 0.
template <typename F>
Eigen::Matrix<double, Eigen::Dynamic, 6> numeric_jacobian(const SE3& T, F f) {
  constexpr double h = 1e-6;
  const auto r0 = f(T);
  Eigen::Matrix<double, Eigen::Dynamic, 6> J(r0.rows(), 6);
  for (int i = 0; i < 6; ++i) {
    const Vec6 d = Vec6::Unit(i) * h;
    J.col(i) = (f(T * SE3::exp(d)) - f(T * SE3::exp(-d))) / (2.0 * h);
  }
  return J;
}

TEST(Residuals, EdgeJacobianMatchesNumeric) {
  std::mt19937 rng(3);
  for (int trial = 0; trial < 20; ++trial) {
    const SE3 T = SE3::exp(random_vec6(rng, 1.0));
    const Vec6 a = random_vec6(rng, 5.0);
    const EdgeCorrespondence c{a.head<3>(), a.tail<3>(), random_vec6(rng, 1.0).head<3>().normalized()};
    Jacobian3x6 J;
    edge_residual(T, c, &J);
    const auto Jn = numeric_jacobian(T, [&](const SE3& X) { return Eigen::VectorXd(edge_residual(X, c)); });
    EXPECT_LT((J - Jn).cwiseAbs().maxCoeff(), 1e-6) << "analytic\n" << J << "\nnumeric\n" << Jn;
  }
}

TEST(Residuals, PlaneJacobianMatchesNumeric) {
  std::mt19937 rng(4);
  for (int trial = 0; trial < 20; ++trial) {
    const SE3 T = SE3::exp(random_vec6(rng, 1.0));
    const Vec6 a = random_vec6(rng, 5.0);
    const PlaneCorrespondence c{a.head<3>(), a.tail<3>().normalized(), a(0)};
    Jacobian1x6 J;
    plane_residual(T, c, &J);
    const auto Jn = numeric_jacobian(T, [&](const SE3& X) { return Eigen::VectorXd::Constant(1, plane_residual(X, c)); });
    EXPECT_LT((J - Jn).cwiseAbs().maxCoeff(), 1e-6) << "analytic\n" << J << "\nnumeric\n" << Jn;
  }
}

TEST(Residuals, TiltJacobianMatchesNumeric) {
  std::mt19937 rng(5);
  for (int trial = 0; trial < 20; ++trial) {
    const SE3 T = SE3::exp(random_vec6(rng, 1.0));
    const Vec3 up_L_prior = random_vec6(rng, 1.0).head<3>().normalized();
    Jacobian3x6 J;
    tilt_residual(T, up_L_prior, &J);
    const auto Jn = numeric_jacobian(T, [&](const SE3& X) { return Eigen::VectorXd(tilt_residual(X, up_L_prior)); });
    EXPECT_LT((J - Jn).cwiseAbs().maxCoeff(), 1e-6) << "analytic\n" << J << "\nnumeric\n" << Jn;
  }
}

TEST(Residuals, TiltSeesRollAndPitchNotYawOrTranslation) {
  const SE3 T(so3::exp(Vec3(0.02, -0.01, 0.7)), Vec3(1, 2, 3));
  const Vec3 up_L = T.rotation().transpose() * Vec3::UnitZ();
  EXPECT_LT(tilt_residual(T, up_L).norm(), 1e-15);
  // A yaw of the world and any translation leave the up direction in L unchanged.
  const SE3 yawed_moved = SE3(so3::exp(Vec3(0, 0, 1.1)), Vec3(-4, 5, 6)) * T;
  EXPECT_LT(tilt_residual(yawed_moved, up_L).norm(), 1e-12);
  // A pitch of 0.01 rad: a residual of norm 2 sin(0.005) ~ 0.01.
  const SE3 pitched = SE3(so3::exp(Vec3(0, 0.01, 0)), Vec3::Zero()) * T;
  EXPECT_NEAR(tilt_residual(pitched, up_L).norm(), 2.0 * std::sin(0.005), 1e-12);
}

TEST(Residuals, AreTheDistancesToLineAndPlane) {
  const SE3 T(Quat::Identity(), Vec3(1, 0, 0));
  // Point (1,2,3) in L is (2,2,3) in W: sqrt(8) from the z axis and 2 above the plane z = 1.
  const EdgeCorrespondence e{Vec3(1, 2, 3), Vec3(0, 0, -7), Vec3::UnitZ()};
  EXPECT_NEAR(edge_residual(T, e).norm(), std::sqrt(8.0), 1e-12);
  const PlaneCorrespondence p{Vec3(1, 2, 3), Vec3::UnitZ(), -1.0};
  EXPECT_NEAR(plane_residual(T, p), 2.0, 1e-12);
}

}  // namespace
}  // namespace vilslam::lidar
