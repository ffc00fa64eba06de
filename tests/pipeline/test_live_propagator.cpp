// The real-time mode's live IMU-rate propagation (pipeline/live_propagator.h) against the VIO's Propagator
// anchored on the same states: nothing before a state arrives, then exactly the propagation from the newest
// state handed over, re-anchored at the next sample after a new one.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "pipeline/live_propagator.h"
#include "pipeline/realtime.h"

namespace vilslam {
namespace {

constexpr TimeNs kStepNs = 5'000'000;  // 200 Hz

ImuSample sample_at(int k) {
  const double t = k * 0.005;
  ImuSample s;
  s.t_ns = k * kStepNs;
  s.gyro_rad_s = Vec3(0.1 * std::sin(t), 0.2, -0.3 * std::cos(2 * t));
  s.accel_m_s2 = Vec3(0.5 * std::cos(t), 0.2, 9.81 + 0.1 * std::sin(3 * t));
  return s;
}

NavState state_at(TimeNs t_ns, double yaw_rad, double speed_m_s) {
  NavState x;
  x.t_ns = t_ns;
  x.R_W_I = Eigen::AngleAxisd(yaw_rad, Vec3::UnitZ()).toRotationMatrix();
  x.p_W_I = Vec3(1.0, -2.0, 0.5);
  x.v_W_m_s = Vec3(speed_m_s, 0.0, 0.1);
  x.bias_gyro_rad_s = Vec3(0.001, -0.002, 0.0005);
  x.bias_accel_m_s2 = Vec3(0.02, 0.0, -0.01);
  return x;
}

// The pose the VIO's propagator gives at sample k from `anchor` and every sample up to k.
SE3 reference_pose(const NavState& anchor, int k) {
  std::vector<ImuSample> samples;
  for (int j = 0; j <= k; ++j) samples.push_back(sample_at(j));
  Propagator reference(ImuNoise{}, Vec3(0, 0, -9.81));
  reference.reset(anchor, samples);
  return reference.current().T_W_I();
}

double gap(const SE3& a, const SE3& b) {
  return (a.translation() - b.translation()).norm() + so3::log(a.quat().conjugate() * b.quat()).norm();
}

TEST(LivePropagator, PropagatesFromTheNewestStateHandedOver) {
  LivePropagator live(ImuNoise{}, Vec3(0, 0, -9.81));
  for (int k = 0; k < 40; ++k) EXPECT_FALSE(live.add(sample_at(k))) << "no state yet, sample " << k;
  const NavState first = state_at(100 * kStepNs + 2'000'000, 0.3, 1.0);  // between samples 100 and 101
  live.anchor(first);
  for (int k = 40; k <= 100; ++k) EXPECT_FALSE(live.add(sample_at(k))) << "sample " << k << " is not after the state";
  for (int k = 101; k < 160; ++k) {
    const std::optional<SE3> pose = live.add(sample_at(k));
    ASSERT_TRUE(pose) << k;
    EXPECT_LT(gap(*pose, reference_pose(first, k)), 1e-9) << k;
  }
  // A newer state, handed over late (the smoother took its time): the next sample re-anchors on it.
  const NavState second = state_at(150 * kStepNs, -0.2, 0.5);
  live.anchor(second);
  for (int k = 160; k < 200; ++k) {
    const std::optional<SE3> pose = live.add(sample_at(k));
    ASSERT_TRUE(pose) << k;
    EXPECT_LT(gap(*pose, reference_pose(second, k)), 1e-9) << k;
    EXPECT_GT(gap(*pose, reference_pose(first, k)), 1e-3) << k;
  }
}

TEST(SensorClock, LatenessAndLatencyCountFromTheDueInstant) {
  EXPECT_THROW(SensorClock(0, 0.0), std::invalid_argument);
  const SensorClock clock(1'000'000'000, 10.0);    // 10x: 1 s of sensor time is due after 100 ms
  EXPECT_GT(clock.wait_until(0), 0.0);             // due before the start: already late
  EXPECT_EQ(clock.wait_until(1'500'000'000), 0.0); // due in 50 ms: waits, not late
  EXPECT_GE(clock.since_ms(1'500'000'000), 0.0);   // so it is due now or past
  EXPECT_LT(clock.since_ms(1'000'000'000'000), 0.0);  // far in the future: not due yet
}

}  // namespace
}  // namespace vilslam
