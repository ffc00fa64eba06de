// Analytic Jacobians of every factor against central differences on the state manifold (boxplus).
#include <gtest/gtest.h>

#include <functional>
#include <random>

#include "analytic_motion.h"
#include "vio/imu_factor.h"
#include "vio/prior.h"
#include "vio/vision_factor.h"

namespace vilslam {
namespace {

using Residual = std::function<Eigen::VectorXd(const std::vector<NavState>&)>;

// d residual / d dx_k for every state k, by central differences through boxplus.
Eigen::MatrixXd numeric_jacobian(const Residual& f, const std::vector<NavState>& states, double h = 1e-6) {
  const int rows = static_cast<int>(f(states).size());
  Eigen::MatrixXd J(rows, kStateDim * static_cast<int>(states.size()));
  for (size_t k = 0; k < states.size(); ++k) {
    for (int d = 0; d < kStateDim; ++d) {
      std::vector<NavState> plus = states, minus = states;
      plus[k] = boxplus(states[k], Vec15::Unit(d) * h);
      minus[k] = boxplus(states[k], -Vec15::Unit(d) * h);
      J.col(kStateDim * static_cast<int>(k) + d) = (f(plus) - f(minus)) / (2 * h);
    }
  }
  return J;
}

NavState random_state(std::mt19937& rng, TimeNs t_ns) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  auto v3 = [&](double s) -> Vec3 { return Vec3(u(rng), u(rng), u(rng)) * s; };
  NavState x;
  x.t_ns = t_ns;
  x.R_W_I = so3::exp(v3(2.0));
  x.p_W_I = v3(3.0);
  x.v_W_m_s = v3(1.0);
  x.bias_gyro_rad_s = v3(0.05);
  x.bias_accel_m_s2 = v3(0.3);
  return x;
}

double relative_error(const Eigen::MatrixXd& analytic, const Eigen::MatrixXd& numeric) {
  return (analytic - numeric).norm() / std::max(1.0, numeric.norm());
}

TEST(Jacobians, ImuFactor) {
  const test::AnalyticMotion motion;
  std::mt19937 rng(3);
  Preintegration p(Vec3(0.01, 0.0, -0.01), Vec3(0.05, -0.1, 0.02), ImuNoise{});
  for (int k = 0; k < 100; ++k) {
    const ImuSample s = motion.imu(0.2 + 0.005 * k);
    p.integrate(s.gyro_rad_s, s.accel_m_s2, 0.005);
  }
  const Vec3 g(0, 0, -9.81);
  for (int trial = 0; trial < 5; ++trial) {
    // States near each other with biases off the preintegration's linearization point.
    std::vector<NavState> x = {random_state(rng, 0), random_state(rng, s_to_ns(0.5))};
    const Residual f = [&](const std::vector<NavState>& s) -> Eigen::VectorXd {
      return imu_residual(p, s[0], s[1], g).r;
    };
    const ImuResidual res = imu_residual(p, x[0], x[1], g);
    Eigen::MatrixXd analytic(9, 2 * kStateDim);
    analytic << res.J_i, res.J_j;
    EXPECT_LT(relative_error(analytic, numeric_jacobian(f, x)), 1e-6) << "trial " << trial;
  }
}

TEST(Jacobians, ImuResidualVanishesAtTheTruth) {
  const test::AnalyticMotion motion;
  Preintegration p(Vec3::Zero(), Vec3::Zero(), ImuNoise{});
  std::vector<ImuSample> samples;
  for (int k = 0; k <= 400; ++k) samples.push_back(motion.imu(0.0025 * k));
  integrate_samples(samples, s_to_ns(0.1), s_to_ns(0.6), p);
  const ImuResidual res = imu_residual(p, motion.state(0.1), motion.state(0.6), Vec3(0, 0, -9.81));
  EXPECT_LT(res.r.norm(), 2e-3);
  // A 5 cm error in the second position shows up in r_p.
  NavState moved = motion.state(0.6);
  moved.p_W_I.x() += 0.05;
  EXPECT_NEAR(imu_residual(p, motion.state(0.1), moved, Vec3(0, 0, -9.81)).r.tail<3>().norm(), 0.05, 3e-3);
}

TEST(Jacobians, BiasFactor) {
  std::mt19937 rng(4);
  std::vector<NavState> x = {random_state(rng, 0), random_state(rng, 1)};
  const Residual f = [](const std::vector<NavState>& s) -> Eigen::VectorXd { return bias_residual(s[0], s[1]).r; };
  const BiasResidual res = bias_residual(x[0], x[1]);
  Eigen::MatrixXd analytic(6, 2 * kStateDim);
  analytic << res.J_i, res.J_j;
  EXPECT_LT(relative_error(analytic, numeric_jacobian(f, x)), 1e-8);
}

TEST(Jacobians, PriorFactor) {
  std::mt19937 rng(5);
  PriorFactor prior;
  prior.state_ids = {3, 4};
  prior.x_lin = {random_state(rng, 0), random_state(rng, 1)};
  std::normal_distribution<double> gauss;
  prior.J0 = Eigen::MatrixXd::NullaryExpr(20, 2 * kStateDim, [&]() { return gauss(rng); });
  prior.r0 = Eigen::VectorXd::NullaryExpr(20, [&]() { return gauss(rng); });
  // Evaluate away from the linearization point, where d(x [-] x_lin)/dx is not the identity.
  std::vector<NavState> x = {boxplus(prior.x_lin[0], Vec15::Constant(0.2)), boxplus(prior.x_lin[1], Vec15::Constant(-0.3))};
  const Residual f = [&](const std::vector<NavState>& s) -> Eigen::VectorXd { return prior_residual(prior, s).r; };
  EXPECT_LT(relative_error(prior_residual(prior, x).J, numeric_jacobian(f, x)), 1e-6);
  EXPECT_LT((prior_residual(prior, prior.x_lin).r - prior.r0).norm(), 1e-12);
}

// The [dphi, dp] columns of a Jacobian over whole states; the other columns must be zero.
Eigen::MatrixXd pose_columns(const Eigen::MatrixXd& J) {
  const int m = static_cast<int>(J.cols()) / kStateDim;
  Eigen::MatrixXd out(J.rows(), 6 * m);
  for (int k = 0; k < m; ++k) {
    out.middleCols(6 * k, 6) = J.middleCols(kStateDim * k, 6);
    EXPECT_LT(J.middleCols(kStateDim * k + 6, kStateDim - 6).norm(), 1e-6 * std::max(1.0, J.norm()));
  }
  return out;
}

// Three states along the analytic motion observing one landmark in both cameras.
struct LandmarkScene {
  std::vector<NavState> states;
  std::vector<StereoObservation> obs;
  Vec3 x_W;
  StereoExtrinsics extr = test::test_extrinsics();
};

LandmarkScene landmark_scene(double noise) {
  const test::AnalyticMotion motion;
  LandmarkScene scene;
  std::mt19937 rng(11);
  for (double t : {0.5, 0.9, 1.3}) scene.states.push_back(motion.state(t));
  // A point 5 m ahead of the middle state's left camera.
  scene.x_W = scene.states[1].T_W_I() * scene.extr.T_I_C0 * Vec3(0.3, -0.2, 5.0);
  for (int k = 0; k < 3; ++k) {
    const FrontendOutput seen = test::observe(scene.states[k], {scene.x_W}, scene.extr, noise, rng);
    EXPECT_EQ(seen.matches.size(), 1u);
    scene.obs.push_back({k, seen.matches[0].left_norm, seen.matches[0].right_norm});
  }
  return scene;
}

TEST(Jacobians, VisionFactorStackedResidual) {
  const LandmarkScene s = landmark_scene(1e-3);
  const double sigma = 1.0 / 450.0;
  const LandmarkLinearization lin = linearize_landmark(s.obs, s.states, s.extr, s.x_W, sigma);
  const Residual f = [&](const std::vector<NavState>& st) -> Eigen::VectorXd {
    return linearize_landmark(s.obs, st, s.extr, s.x_W, sigma).stacked_b();
  };
  EXPECT_LT(relative_error(lin.stacked_F(), pose_columns(numeric_jacobian(f, s.states))), 1e-6);
  Eigen::MatrixXd E_numeric(lin.stacked_b().size(), 3);
  for (int d = 0; d < 3; ++d) {
    const Vec3 h = Vec3::Unit(d) * 1e-6;
    E_numeric.col(d) = (linearize_landmark(s.obs, s.states, s.extr, s.x_W + h, sigma).stacked_b() -
                        linearize_landmark(s.obs, s.states, s.extr, s.x_W - h, sigma).stacked_b()) / 2e-6;
  }
  EXPECT_LT(relative_error(lin.stacked_E(), E_numeric), 1e-6);
}

TEST(Jacobians, StructurelessFactorIsTheNullSpaceProjection) {
  const LandmarkScene s = landmark_scene(2e-3);
  const double sigma = 1.0 / 450.0;
  const std::optional<Vec3> x_W = triangulate(s.obs, s.states, s.extr);
  ASSERT_TRUE(x_W.has_value());
  EXPECT_LT((*x_W - s.x_W).norm(), 0.3);
  const LandmarkLinearization lin = linearize_landmark(s.obs, s.states, s.extr, *x_W, sigma);
  const LinearFactor f = structureless_factor(s.obs, lin);
  // Explicit Q_p = I - E (E^T E)^-1 E^T (paper eq. (4)).
  const Eigen::VectorXd b = lin.stacked_b();
  const Eigen::MatrixXd E = lin.stacked_E();
  const Eigen::MatrixXd Q = Eigen::MatrixXd::Identity(b.size(), b.size()) - E * (E.transpose() * E).inverse() * E.transpose();
  EXPECT_LT((Q * E).norm(), 1e-8 * E.norm());
  const Eigen::MatrixXd QF = Q * lin.stacked_F();
  EXPECT_LT(relative_error(f.H, QF.transpose() * QF), 1e-9);
  EXPECT_LT(relative_error(f.g, QF.transpose() * Q * b), 1e-9);
  EXPECT_NEAR(f.cost, (Q * b).squaredNorm(), 1e-9 * std::max(1.0, f.cost));
  // Q_p F_p is the Jacobian of the residual with the landmark re-triangulated at every state, projected
  // by the fixed Q_p: Q d b(x, x_p*(x))/dx = Q (F + E dx_p*/dx) = Q F.
  const Residual retriangulated = [&](const std::vector<NavState>& st) -> Eigen::VectorXd {
    const std::optional<Vec3> p = triangulate(s.obs, st, s.extr);
    return Q * linearize_landmark(s.obs, st, s.extr, *p, sigma).stacked_b();
  };
  EXPECT_LT(relative_error(QF, pose_columns(numeric_jacobian(retriangulated, s.states, 1e-7))), 1e-4);
}

}  // namespace
}  // namespace vilslam
