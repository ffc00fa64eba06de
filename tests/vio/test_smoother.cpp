// The fixed-lag smoother on synthetic stereo observations and IMU samples of the analytic motion.
#include <gtest/gtest.h>

#include <cstdio>
#include <random>

#include "analytic_motion.h"
#include "vio/imu_factor.h"
#include "vio/smoother.h"

namespace vilslam {
namespace {

constexpr double kFocalPx = 450.0;

struct SmootherRun {
  std::vector<double> position_error_m;    // newest state vs truth after each frame
  std::vector<double> rotation_error_deg;
  double max_resolve_shift_m = 0;          // re-solving right after a marginalization moves the window by this
  int marginalizations = 0;
  SmootherStats stats;
  Mat15 newest_covariance;
  NavState newest, truth;
};

// Observations of the truth; tracks with id % outlier_modulus == 0 get 8 px of noise on the left image.
FrontendOutput observe_with_outliers(const NavState& truth, const std::vector<Vec3>& landmarks,
                                     const StereoExtrinsics& extr, double sigma_norm, int outlier_modulus,
                                     std::mt19937& rng) {
  FrontendOutput out = test::observe(truth, landmarks, extr, sigma_norm, rng);
  std::normal_distribution<double> gross(0.0, 8.0 / kFocalPx);
  for (StereoMatch& m : out.matches) {
    if (outlier_modulus > 0 && m.track_id % outlier_modulus == 0) m.left_norm += Eigen::Vector2d(gross(rng), gross(rng));
  }
  return out;
}

SmootherRun run_smoother(int frames, int window, std::uint32_t seed, int outlier_modulus = 0,
                         double outlier_normal_quantile = SmootherConfig{}.outlier_normal_quantile) {
  const test::AnalyticMotion motion;
  const StereoExtrinsics extr = test::test_extrinsics();
  const std::vector<Vec3> landmarks = test::test_landmarks(400, seed);
  std::mt19937 rng(seed);
  std::normal_distribution<double> gauss(0.0, 1.0);
  ImuNoise noise;
  const Vec3 bg(0.003, -0.002, 0.004), ba(0.05, -0.03, 0.04);
  const double imu_dt = 1.0 / noise.rate_hz;
  const double t0 = 0.5, frame_dt = 0.1;

  // IMU samples with biases and white noise over the whole run.
  std::vector<ImuSample> imu;
  for (double t = t0 - 0.05; t < t0 + frame_dt * frames + 0.05; t += imu_dt) {
    ImuSample s = motion.imu(t);
    s.gyro_rad_s += bg + Vec3(gauss(rng), gauss(rng), gauss(rng)) * noise.gyro_noise_density / std::sqrt(imu_dt);
    s.accel_m_s2 += ba + Vec3(gauss(rng), gauss(rng), gauss(rng)) * noise.accel_noise_density / std::sqrt(imu_dt);
    imu.push_back(s);
  }

  SmootherConfig config;
  config.window_size = window;
  config.pixel_sigma_px = 0.5;
  config.outlier_normal_quantile = outlier_normal_quantile;
  Smoother smoother(config, extr, noise, kFocalPx);
  const double sigma_norm = config.pixel_sigma_px / kFocalPx;
  NavState x0 = motion.state(t0);
  Vec15 sigma;
  sigma << Vec3::Constant(1e-3), Vec3::Constant(1e-3), Vec3::Constant(0.01), Vec3::Constant(0.01),
      Vec3::Constant(0.1);
  smoother.initialize(x0, sigma, observe_with_outliers(x0, landmarks, extr, sigma_norm, outlier_modulus, rng));

  SmootherRun run;
  for (int k = 1; k <= frames; ++k) {
    const NavState truth = motion.state(t0 + frame_dt * k);
    const NavState& last = smoother.newest();
    Preintegration preint(last.bias_gyro_rad_s, last.bias_accel_m_s2, noise);
    integrate_samples(imu, last.t_ns, truth.t_ns, preint);
    smoother.add_frame(preint, observe_with_outliers(truth, landmarks, extr, sigma_norm, outlier_modulus, rng));
    const NavState& est = smoother.newest();
    run.position_error_m.push_back((est.p_W_I - truth.p_W_I).norm());
    run.rotation_error_deg.push_back(so3::log(Mat3(est.R_W_I.transpose() * truth.R_W_I)).norm() * 180 / M_PI);
    if (k >= window) {
      ++run.marginalizations;
      const std::vector<NavState> before = smoother.window_states();
      smoother.optimize();
      const std::vector<NavState> after = smoother.window_states();
      for (size_t i = 0; i < before.size(); ++i) {
        run.max_resolve_shift_m = std::max(run.max_resolve_shift_m, (after[i].p_W_I - before[i].p_W_I).norm());
      }
    }
    run.truth = truth;
  }
  run.stats = smoother.stats();
  run.newest = smoother.newest();
  run.newest_covariance = smoother.newest_covariance();
  return run;
}

TEST(Smoother, TracksSyntheticMotionThroughMarginalization) {
  const SmootherRun run = run_smoother(40, 10, 21);
  const double max_pos = *std::max_element(run.position_error_m.begin(), run.position_error_m.end());
  const double max_rot = *std::max_element(run.rotation_error_deg.begin(), run.rotation_error_deg.end());
  std::printf("40 frames, window 10: max position error %.4f m, final %.4f m, max rotation error %.3f deg\n",
              max_pos, run.position_error_m.back(), max_rot);
  std::printf("  landmarks in last solve %d, rejected %d, LM iterations %d, max shift on re-solve %.2e m\n",
              run.stats.landmarks, run.stats.rejected_landmarks, run.stats.lm_iterations, run.max_resolve_shift_m);
  EXPECT_EQ(run.marginalizations, 31);
  EXPECT_LT(max_pos, 0.05);
  EXPECT_LT(max_rot, 0.5);
  EXPECT_GT(run.stats.landmarks, 30);
  // The marginalization prior carries the dropped state's information: re-solving right after
  // marginalizing does not move the window.
  EXPECT_LT(run.max_resolve_shift_m, 2e-3);
  // The reported covariance covers the actual error (position, 4 sigma).
  const Vec3 err = run.newest.p_W_I - run.truth.p_W_I;
  for (int k = 0; k < 3; ++k) {
    EXPECT_LT(std::abs(err[k]), 4 * std::sqrt(run.newest_covariance(kPos + k, kPos + k)) + 1e-3);
  }
}

TEST(Smoother, RejectsGrossOutliersWithTheChiSquareTest) {
  auto max_error = [](const SmootherRun& run) {
    return *std::max_element(run.position_error_m.begin(), run.position_error_m.end());
  };
  // One track in ten is an outlier; a huge quantile switches the chi-square test off.
  const SmootherRun with_test = run_smoother(20, 10, 33, 10);
  const SmootherRun without_test = run_smoother(20, 10, 33, 10, 1e6);
  std::printf("outliers: chi-square test on: rejected %d landmarks, max position error %.4f m; off: %.4f m\n",
              with_test.stats.rejected_landmarks, max_error(with_test), max_error(without_test));
  EXPECT_EQ(without_test.stats.rejected_landmarks, 0);
  EXPECT_GT(with_test.stats.rejected_landmarks, 5);
  EXPECT_LT(max_error(with_test), 0.03);
  EXPECT_GT(max_error(without_test), 2 * max_error(with_test));
}

TEST(Smoother, IsDeterministic) {
  const SmootherRun a = run_smoother(14, 5, 5), b = run_smoother(14, 5, 5);
  EXPECT_EQ(a.newest.p_W_I, b.newest.p_W_I);
  EXPECT_EQ(a.newest.R_W_I, b.newest.R_W_I);
  EXPECT_EQ(a.newest_covariance, b.newest_covariance);
}

TEST(TiltSigma, ReadsRollAndPitchAndLeavesOutTheYaw) {
  NavState x;
  x.R_W_I = so3::exp(Vec3(0.3, -0.2, 1.0));  // tilted, so the body axes mix world yaw and tilt
  const Mat3 R_I_W = x.R_W_I.transpose();
  // Attitude covariance (right perturbation, body frame): 1 deg about the world's x and y, and a yaw variance
  // that is garbage, huge or negative (a gauge the solver's covariance does not fix).
  const double sigma = 0.0175;
  for (const double yaw_variance : {1e4, -3.0}) {
    Mat3 C_W = Mat3::Zero();
    C_W.diagonal() << sigma * sigma, 0.25 * sigma * sigma, yaw_variance;
    Mat15 covariance = Mat15::Zero();
    covariance.block<3, 3>(kRot, kRot) = R_I_W * C_W * R_I_W.transpose();
    EXPECT_NEAR(tilt_sigma_rad(x, covariance), sigma, 1e-9);
  }
  Mat15 covariance = Mat15::Identity();
  covariance(0, 1) = std::nan("");
  EXPECT_EQ(tilt_sigma_rad(x, covariance), 0.0);
}

}  // namespace
}  // namespace vilslam
