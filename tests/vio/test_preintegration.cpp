#include <gtest/gtest.h>

#include <random>

#include "analytic_motion.h"
#include "vio/imu_factor.h"
#include "vio/preintegration.h"

namespace vilslam {
namespace {

const Vec3 kGravity(0, 0, -9.81);

std::vector<ImuSample> sample_motion(const test::AnalyticMotion& motion, double t0_s, double t1_s, double rate_hz,
                                     const Vec3& bg, const Vec3& ba) {
  std::vector<ImuSample> samples;
  for (double t = t0_s; t <= t1_s + 1e-9; t += 1.0 / rate_hz) {
    ImuSample s = motion.imu(t);
    s.gyro_rad_s += bg;
    s.accel_m_s2 += ba;
    samples.push_back(s);
  }
  return samples;
}

Preintegration preintegrate(const std::vector<ImuSample>& samples, TimeNs t0, TimeNs t1, const Vec3& bg,
                            const Vec3& ba) {
  Preintegration p(bg, ba, ImuNoise{});
  integrate_samples(samples, t0, t1, p);
  return p;
}

TEST(Preintegration, NoiselessSamplesPredictTheTrueState) {
  const test::AnalyticMotion motion;
  const Vec3 bg(0.01, -0.02, 0.015), ba(0.1, -0.05, 0.08);
  const auto samples = sample_motion(motion, 0.0, 2.0, 1000.0, bg, ba);
  NavState x0 = motion.state(0.3);
  x0.bias_gyro_rad_s = bg;
  x0.bias_accel_m_s2 = ba;
  const NavState truth = motion.state(1.3);
  const Preintegration p = preintegrate(samples, x0.t_ns, truth.t_ns, bg, ba);
  EXPECT_NEAR(p.dt_s(), 1.0, 1e-12);
  const NavState x1 = predict_state(p, x0, kGravity);
  EXPECT_EQ(x1.t_ns, truth.t_ns);
  EXPECT_LT((x1.p_W_I - truth.p_W_I).norm(), 1e-3);
  EXPECT_LT((x1.v_W_m_s - truth.v_W_m_s).norm(), 2e-3);
  EXPECT_LT(so3::log(Mat3(x1.R_W_I.transpose() * truth.R_W_I)).norm(), 1e-4);
  // Ignoring the biases breaks the prediction.
  x0.bias_accel_m_s2.setZero();
  x0.bias_gyro_rad_s.setZero();
  const NavState wrong = predict_state(preintegrate(samples, x0.t_ns, truth.t_ns, Vec3::Zero(), Vec3::Zero()), x0,
                                       kGravity);
  EXPECT_GT((wrong.p_W_I - truth.p_W_I).norm(), 0.03);
}

TEST(Preintegration, SplitIntervalsComposeToTheWhole) {
  const test::AnalyticMotion motion;
  const auto samples = sample_motion(motion, 0.0, 1.0, 200.0, Vec3::Zero(), Vec3::Zero());
  // Ends between samples (200 Hz = 5 ms grid), the split on a sample: the same Euler steps either way.
  const TimeNs t0 = 101'300'000, t1 = 435'000'000, t2 = 871'100'000;
  NavState x0 = motion.state(ns_to_s(t0));
  const NavState whole = predict_state(preintegrate(samples, t0, t2, Vec3::Zero(), Vec3::Zero()), x0, kGravity);
  const NavState mid = predict_state(preintegrate(samples, t0, t1, Vec3::Zero(), Vec3::Zero()), x0, kGravity);
  const NavState end = predict_state(preintegrate(samples, t1, t2, Vec3::Zero(), Vec3::Zero()), mid, kGravity);
  EXPECT_LT((whole.p_W_I - end.p_W_I).norm(), 1e-9);
  EXPECT_LT((whole.v_W_m_s - end.v_W_m_s).norm(), 1e-9);
  EXPECT_LT(so3::log(Mat3(whole.R_W_I.transpose() * end.R_W_I)).norm(), 1e-9);
}

TEST(Preintegration, BiasJacobiansCorrectToFirstOrder) {
  const test::AnalyticMotion motion;
  const auto samples = sample_motion(motion, 0.0, 1.5, 200.0, Vec3::Zero(), Vec3::Zero());
  const TimeNs t0 = s_to_ns(0.2), t1 = s_to_ns(1.2);
  const Vec3 bg0(0.002, -0.001, 0.003), ba0(0.05, 0.02, -0.03);
  const Preintegration p = preintegrate(samples, t0, t1, bg0, ba0);
  for (double scale : {1e-3, 2e-3}) {
    const Vec3 dbg = scale * Vec3(1.0, -2.0, 0.5), dba = 10 * scale * Vec3(-1.0, 0.5, 2.0);
    const Preintegration exact = preintegrate(samples, t0, t1, bg0 + dbg, ba0 + dba);
    const double change_R = so3::log(Mat3(p.delta_R().transpose() * exact.delta_R())).norm();
    const double err_R = so3::log(Mat3(p.corrected_delta_R(bg0 + dbg).transpose() * exact.delta_R())).norm();
    const double change_v = (exact.delta_v() - p.delta_v()).norm();
    const double err_v = (p.corrected_delta_v(bg0 + dbg, ba0 + dba) - exact.delta_v()).norm();
    const double change_p = (exact.delta_p() - p.delta_p()).norm();
    const double err_p = (p.corrected_delta_p(bg0 + dbg, ba0 + dba) - exact.delta_p()).norm();
    // First order: the remaining error is a small fraction of the change (it scales with the change squared).
    EXPECT_LT(err_R, 0.01 * change_R);
    EXPECT_LT(err_v, 0.01 * change_v);
    EXPECT_LT(err_p, 0.01 * change_p);
  }
}

TEST(Preintegration, CovarianceMatchesMonteCarlo) {
  const test::AnalyticMotion motion;
  const double rate = 200.0, dt = 1.0 / rate;
  const auto clean = sample_motion(motion, 0.0, 1.0, rate, Vec3::Zero(), Vec3::Zero());
  ImuNoise noise;
  noise.gyro_noise_density = 0.01;
  noise.accel_noise_density = 0.1;
  Preintegration reference(Vec3::Zero(), Vec3::Zero(), noise);
  for (size_t k = 0; k + 1 < clean.size(); ++k) reference.integrate(clean[k].gyro_rad_s, clean[k].accel_m_s2, dt);

  std::mt19937 rng(7);
  std::normal_distribution<double> gauss(0.0, 1.0);
  const int runs = 400;
  Eigen::Matrix<double, 9, 9> empirical = Eigen::Matrix<double, 9, 9>::Zero();
  for (int run = 0; run < runs; ++run) {
    Preintegration p(Vec3::Zero(), Vec3::Zero(), noise);
    for (size_t k = 0; k + 1 < clean.size(); ++k) {
      const Vec3 ng(gauss(rng), gauss(rng), gauss(rng)), na(gauss(rng), gauss(rng), gauss(rng));
      p.integrate(clean[k].gyro_rad_s + ng * noise.gyro_noise_density / std::sqrt(dt),
                  clean[k].accel_m_s2 + na * noise.accel_noise_density / std::sqrt(dt), dt);
    }
    // Forster eq. (42): dphi from Exp(-dphi) = dR_true^T dR_meas ... here the noise enters as dR_meas Exp(-dphi).
    Eigen::Matrix<double, 9, 1> e;
    e << so3::log(Mat3(p.delta_R().transpose() * reference.delta_R())), p.delta_v() - reference.delta_v(),
        p.delta_p() - reference.delta_p();
    empirical += e * e.transpose() / runs;
  }
  const Eigen::Matrix<double, 9, 9>& predicted = reference.covariance();
  for (int i = 0; i < 9; ++i) {
    EXPECT_NEAR(empirical(i, i) / predicted(i, i), 1.0, 0.25) << "diagonal entry " << i;
  }
}

TEST(ImuSamples, DroppingBeforeATimeKeepsTheSampleWhoseIntervalHoldsIt) {
  std::vector<ImuSample> samples;
  for (const TimeNs t : {10, 20, 30, 40}) samples.push_back(ImuSample{t, Vec3::Zero(), Vec3::Zero()});
  EXPECT_EQ(first_sample_after(samples, 20)->t_ns, 30);
  EXPECT_EQ(first_sample_after(samples, 5)->t_ns, 10);
  EXPECT_TRUE(first_sample_after(samples, 40) == samples.end());
  std::vector<ImuSample> kept = samples;
  drop_samples_before(kept, 25);  // 20 stays: integrating from 25 starts in [20, 30]
  ASSERT_EQ(kept.size(), 3u);
  EXPECT_EQ(kept.front().t_ns, 20);
  kept = samples;
  drop_samples_before(kept, 30);
  EXPECT_EQ(kept.front().t_ns, 30);
  kept = samples;
  drop_samples_before(kept, 5);  // nothing at or before: all kept
  EXPECT_EQ(kept.size(), 4u);
}

// A frame between two samples is integrated the same whether the next sample has arrived or not (live and
// offline agree), unless that sample ends an IMU gap: across a gap it is interpolated towards.
TEST(ImuSamples, AFrameIsIntegratedWithTheSamplesUpToItAndTheOneEndingAGap) {
  std::vector<ImuSample> samples;
  for (const TimeNs t : {0, 5'000'000, 10'000'000, 15'000'000})
    samples.push_back(ImuSample{t, Vec3(0.01 * t * 1e-6, 0, 0), Vec3(0, 0, 9.81)});
  const double max_step_s = 0.012;
  const std::vector<ImuSample> known = samples_for_frame(samples, 8'000'000, max_step_s);
  ASSERT_EQ(known.size(), 2u);  // 0 and 5 ms: the 10 ms sample may or may not have arrived live
  EXPECT_EQ(known.back().t_ns, 5'000'000);
  const auto integrate = [](const std::vector<ImuSample>& s) {
    Preintegration p(Vec3::Zero(), Vec3::Zero(), ImuNoise{});
    integrate_samples(s, 0, 8'000'000, p);
    return p.delta_R();
  };
  const std::vector<ImuSample> arrived(samples.begin(), samples.begin() + 3), not_yet(samples.begin(), samples.begin() + 2);
  EXPECT_EQ(integrate(samples_for_frame(arrived, 8'000'000, max_step_s)),
            integrate(samples_for_frame(not_yet, 8'000'000, max_step_s)));
  EXPECT_NE(integrate(arrived), integrate(not_yet));  // what the raw samples would have given
  // A gap from 5 to 25 ms: the sample ending it is kept.
  std::vector<ImuSample> gapped = {samples[0], samples[1], ImuSample{25'000'000, Vec3::Zero(), Vec3(0, 0, 9.81)}};
  EXPECT_EQ(samples_for_frame(gapped, 8'000'000, max_step_s).size(), 3u);
  EXPECT_EQ(samples_for_frame(samples, 15'000'000, max_step_s).size(), 4u);
}

}  // namespace
}  // namespace vilslam
