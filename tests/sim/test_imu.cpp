#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

#include "sim/imu_sim.h"

namespace vilslam::sim {
namespace {

std::vector<Vec3> square_route() {
  return {Vec3(0, 0, 1.2), Vec3(6, 0, 1.2), Vec3(6, 6, 1.2), Vec3(0, 6, 1.2), Vec3(0, 0, 1.2)};
}

struct NavState {
  Quat q_W_I;
  Vec3 v_W;
  Vec3 p_W;
};

struct NavRate {
  Vec3 omega_I, v_dot, p_dot;
};

NavRate derivative(const NavState& x, const ImuSample& m) {
  return {m.gyro_rad_s, x.q_W_I * m.accel_m_s2 + kGravity_W, x.v_W};
}

NavState advance(const NavState& x, const NavRate& k, double h) {
  const Quat dq = so3::exp_quat(k.omega_I * h);
  return {(x.q_W_I * dq).normalized(), x.v_W + k.v_dot * h, x.p_W + k.p_dot * h};
}

// Classical RK4 over h = 2 / rate with the samples at t, t + h/2 and t + h (the 200 Hz stream supplies
// the midpoint). The attitude stage update q Exp(omega h) is the Lie-group form of q' = q (x) [0, omega/2];
// the k's are combined in the tangent space, which keeps RK4's fourth order for the attitude.
NavState rk4_step(const NavState& x, const ImuSample& m0, const ImuSample& m_mid, const ImuSample& m1, double h) {
  const NavRate k1 = derivative(x, m0);
  const NavRate k2 = derivative(advance(x, k1, h / 2), m_mid);
  const NavRate k3 = derivative(advance(x, k2, h / 2), m_mid);
  const NavRate k4 = derivative(advance(x, k3, h), m1);
  const NavRate k{(k1.omega_I + 2 * k2.omega_I + 2 * k3.omega_I + k4.omega_I) / 6,
                  (k1.v_dot + 2 * k2.v_dot + 2 * k3.v_dot + k4.v_dot) / 6,
                  (k1.p_dot + 2 * k2.p_dot + 2 * k3.p_dot + k4.p_dot) / 6};
  return advance(x, k, h);
}

TEST(ImuSim, NoiseFreeImuIntegratesBackToTheTrajectory) {
  const RouteMotion motion(square_route(), RouteMotionConfig{});
  ImuSimConfig config;
  config.add_noise = false;
  const TimeNs t0 = motion.start_ns() + s_to_ns(0.5);
  const TimeNs t1 = t0 + 10 * kNsPerSecond;
  const ImuSimulation imu = simulate_imu(motion, config, t0, t1);
  ASSERT_EQ(imu.samples.size(), 2001u);
  const MotionState first = motion.state(t0);
  NavState x{first.T_W_I.quat(), first.v_W, first.T_W_I.translation()};
  const double h = 2.0 / config.noise.rate_hz;
  for (std::size_t k = 0; k + 2 < imu.samples.size(); k += 2)
    x = rk4_step(x, imu.samples[k], imu.samples[k + 1], imu.samples[k + 2], h);
  const MotionState last = motion.state(t1);
  const double position_error_m = (x.p_W - last.T_W_I.translation()).norm();
  const double angle_error_deg = so3::log(x.q_W_I.conjugate() * last.T_W_I.quat()).norm() * 180 / M_PI;
  std::cout << "after 10 s: position error " << position_error_m << " m, attitude error " << angle_error_deg
            << " deg\n";
  EXPECT_LT(position_error_m, 0.01);
  EXPECT_LT(angle_error_deg, 0.1);
  // It was a real test: the rig turned and travelled.
  EXPECT_GT((last.T_W_I.translation() - first.T_W_I.translation()).norm(), 3.0);
  EXPECT_GT(so3::log(first.T_W_I.quat().conjugate() * last.T_W_I.quat()).norm(), 0.5);
}

TEST(ImuSim, IdealImuAtRestMeasuresGravityOnly) {
  const RouteMotion motion(square_route(), RouteMotionConfig{});
  const MotionState rest = motion.state(motion.start_ns());
  const ImuSample m = ideal_imu(rest);
  EXPECT_LT(m.gyro_rad_s.norm(), 1e-12);
  EXPECT_LT((rest.T_W_I.quat() * m.accel_m_s2 - Vec3(0, 0, 9.81)).norm(), 1e-12);
}

TEST(ImuSim, NoiseMatchesTheDrawnDensitiesAndIsSeeded) {
  const RouteMotion motion(square_route(), RouteMotionConfig{});
  ImuSimConfig config;
  config.seed = 7;
  config.noise.rate_hz = 400;
  const TimeNs t1 = motion.start_ns() + 30 * kNsPerSecond;
  const ImuSimulation a = simulate_imu(motion, config, motion.start_ns(), t1);
  ASSERT_EQ(a.samples.size(), 12001u);
  EXPECT_EQ(a.samples[1].t_ns - a.samples[0].t_ns, 2'500'000);
  // The true noise is the data sheet's times factors in [0.5, 3], not the data sheet's.
  const ImuNoise& truth = a.errors.noise;
  for (const double factor : {truth.gyro_noise_density / config.noise.gyro_noise_density,
                              truth.accel_noise_density / config.noise.accel_noise_density,
                              truth.gyro_random_walk / config.noise.gyro_random_walk,
                              truth.accel_random_walk / config.noise.accel_random_walk}) {
    EXPECT_GE(factor, 0.5);
    EXPECT_LE(factor, 3.0);
    EXPECT_NE(factor, 1.0);
  }
  // Residual after removing the truth through the drawn axis errors and the known bias is the white noise:
  // std = true density * sqrt(rate).
  double gyro_sq = 0, accel_sq = 0;
  for (std::size_t k = 0; k < a.samples.size(); ++k) {
    const ImuSample ideal = apply_axis_errors(a.errors, ideal_imu(motion.state(a.samples[k].t_ns)));
    gyro_sq += (a.samples[k].gyro_rad_s - ideal.gyro_rad_s - a.groundtruth[k].bias_gyro_rad_s).squaredNorm();
    accel_sq += (a.samples[k].accel_m_s2 - ideal.accel_m_s2 - a.groundtruth[k].bias_accel_m_s2).squaredNorm();
  }
  const double n = 3.0 * a.samples.size();
  EXPECT_NEAR(std::sqrt(gyro_sq / n), truth.gyro_noise_density * 20, 0.03 * truth.gyro_noise_density * 20);
  EXPECT_NEAR(std::sqrt(accel_sq / n), truth.accel_noise_density * 20, 0.03 * truth.accel_noise_density * 20);
  // Biases walk: they change over the sequence.
  EXPECT_GT((a.groundtruth.back().bias_accel_m_s2 - a.groundtruth.front().bias_accel_m_s2).norm(), 1e-3);

  const ImuSimulation same = simulate_imu(motion, config, motion.start_ns(), t1);
  EXPECT_EQ(same.samples.back().accel_m_s2, a.samples.back().accel_m_s2);
  config.seed = 8;
  const ImuSimulation other = simulate_imu(motion, config, motion.start_ns(), t1);
  EXPECT_NE(other.samples.back().accel_m_s2, a.samples.back().accel_m_s2);
  EXPECT_NE(other.errors.noise.gyro_noise_density, truth.gyro_noise_density);
}

// The axis errors stay within their ranges; none drawn, the data sheet's IMU measures exactly.
TEST(ImuErrors, DrawnWithinTheirRangesAndNoneForTheDataSheet) {
  const ImuNoise sheet;
  const ImuErrorRanges ranges;
  for (std::uint64_t seed = 0; seed < 50; ++seed) {
    const ImuErrors e = draw_imu_errors(sheet, ranges, seed);
    for (const Mat3* axes : {&e.gyro_axes, &e.accel_axes}) {
      for (int i = 0; i < 3; ++i) {
        EXPECT_LE(std::abs((*axes)(i, i) - 1.0), ranges.max_scale_error);
        const Vec3 direction = axes->row(i).transpose().normalized();
        EXPECT_LE(std::acos(std::min(1.0, direction(i))) * 180.0 / M_PI, 1.01 * ranges.max_misalignment_deg);  // 1 + scale
      }
    }
    EXPECT_LE(e.g_sensitivity.cwiseAbs().maxCoeff(), ranges.max_g_sensitivity_rad_s_per_m_s2);
  }
  const ImuErrors a = draw_imu_errors(sheet, ranges, 3), b = draw_imu_errors(sheet, ranges, 3);
  EXPECT_EQ(a.gyro_axes, b.gyro_axes);
  EXPECT_NE(a.gyro_axes, draw_imu_errors(sheet, ranges, 4).gyro_axes);

  const ImuErrors none = draw_imu_errors(sheet, no_imu_errors(), 3);
  EXPECT_EQ(none.noise.gyro_noise_density, sheet.gyro_noise_density);
  EXPECT_EQ(none.noise.accel_random_walk, sheet.accel_random_walk);
  ImuSample s;
  s.gyro_rad_s = Vec3(0.3, -1.2, 2.5);
  s.accel_m_s2 = Vec3(-0.4, 9.7, 1.1);
  const ImuSample m = apply_axis_errors(none, s);
  EXPECT_EQ(m.gyro_rad_s, s.gyro_rad_s);  // bit for bit: an ideal dataset is the one of before
  EXPECT_EQ(m.accel_m_s2, s.accel_m_s2);
  // With errors: a rate about x reads on y and z (misalignment) and an acceleration turns the gyro (g-sensitivity).
  const ImuSample r = apply_axis_errors(a, s);
  EXPECT_NE(r.gyro_rad_s, s.gyro_rad_s);
  EXPECT_LT((r.gyro_rad_s - s.gyro_rad_s).norm(), 0.01 * s.gyro_rad_s.norm() + 0.01);
}

}  // namespace
}  // namespace vilslam::sim
