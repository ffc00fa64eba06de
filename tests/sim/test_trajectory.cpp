#include <gtest/gtest.h>

#include <cmath>

#include "sim/trajectory.h"

namespace vilslam::sim {
namespace {

constexpr TimeNs kMs = 1'000'000;

std::vector<Vec3> rectangle_route() {
  return {Vec3(0, 0, 1.5), Vec3(20, 0, 1.5), Vec3(20, 10, 1.5), Vec3(0, 10, 1.5), Vec3(0, 0, 1.5)};
}

double rotation_angle(const SE3& a, const SE3& b) { return so3::log(a.quat().conjugate() * b.quat()).norm(); }

// Central differences of pose and velocity against the analytic velocity, acceleration and body rate.
void expect_consistent_derivatives(const BodyMotion& motion, TimeNs step_ns, double tol_v, double tol_a,
                                   double tol_w) {
  const TimeNs h = kMs / 10;
  const double h_s = ns_to_s(h);
  for (TimeNs t = motion.start_ns() + h; t + h < motion.end_ns(); t += step_ns) {
    const MotionState m = motion.state(t), prev = motion.state(t - h), next = motion.state(t + h);
    const Vec3 v_fd = (next.T_W_I.translation() - prev.T_W_I.translation()) / (2 * h_s);
    const Vec3 a_fd = (next.v_W - prev.v_W) / (2 * h_s);
    const Vec3 w_fd = so3::log(prev.T_W_I.quat().conjugate() * next.T_W_I.quat()) / (2 * h_s);
    ASSERT_LT((v_fd - m.v_W).norm(), tol_v) << "t=" << t;
    ASSERT_LT((a_fd - m.a_W).norm(), tol_a) << "t=" << t;
    ASSERT_LT((w_fd - m.omega_I).norm(), tol_w) << "t=" << t;
  }
}

TEST(RouteMotion, ClosedAndAtRestAtBothEnds) {
  const RouteMotion motion(rectangle_route(), RouteMotionConfig{});
  const MotionState first = motion.state(motion.start_ns()), last = motion.state(motion.end_ns());
  EXPECT_LT((first.T_W_I.translation() - last.T_W_I.translation()).norm(), 1e-6);
  EXPECT_LT(rotation_angle(first.T_W_I, last.T_W_I), 1e-6);
  for (const MotionState& s : {first, last}) {
    EXPECT_LT(s.v_W.norm(), 1e-9);
    EXPECT_LT(s.a_W.norm(), 1e-9);
    EXPECT_LT(s.omega_I.norm(), 1e-9);
  }
  // Moving in between: the rig leaves its start position.
  EXPECT_GT((motion.pose((motion.start_ns() + motion.end_ns()) / 2).translation() - first.T_W_I.translation()).norm(),
            5.0);
}

TEST(RouteMotion, LengthFollowsTheRoute) {
  const RouteMotion motion(rectangle_route(), RouteMotionConfig{});
  // Corners are rounded off over about one control spacing: a little shorter than the 60 m polygon.
  EXPECT_LT(motion.length_m(), 60.0);
  EXPECT_GT(motion.length_m(), 57.0);
  // The distance flown (sum of steps) equals the arc length.
  double flown = 0;
  for (TimeNs t = motion.start_ns(); t < motion.end_ns(); t += 10 * kMs)
    flown += (motion.pose(t + 10 * kMs).translation() - motion.pose(t).translation()).norm();
  EXPECT_NEAR(flown, motion.length_m(), 0.01);
}

TEST(RouteMotion, DerivativesMatchFiniteDifferences) {
  const RouteMotion motion(rectangle_route(), RouteMotionConfig{});
  expect_consistent_derivatives(motion, 37 * kMs, 1e-4, 1e-3, 1e-4);
  // A gentle slope (the outdoor route climbs): pitch follows it.
  std::vector<Vec3> hill = rectangle_route();
  hill[1].z() = 2.5;
  hill[2].z() = 2.5;
  const RouteMotion climbing(hill, RouteMotionConfig{});
  expect_consistent_derivatives(climbing, 37 * kMs, 1e-4, 1e-3, 1e-4);
  const SE3 T = climbing.pose(climbing.start_ns() + s_to_ns(6.0));
  const Vec3 forward_W = T.rotation().col(0), v_W = climbing.state(climbing.start_ns() + s_to_ns(6.0)).v_W;
  EXPECT_GT(v_W.z(), 0.02);
  EXPECT_NEAR(std::asin(forward_W.z()), std::asin(v_W.z() / v_W.norm()), 1.2 * M_PI / 180);  // up to the sway
}

// Largest change of acceleration between samples h apart, and the largest acceleration.
std::pair<double, double> acceleration_steps(const BodyMotion& motion, TimeNs h) {
  double max_jump = 0, max_accel = 0;
  Vec3 a_prev = motion.state(motion.start_ns()).a_W;
  for (TimeNs t = motion.start_ns() + h; t <= motion.end_ns(); t += h) {
    const Vec3 a = motion.state(t).a_W;
    max_jump = std::max(max_jump, (a - a_prev).norm());
    max_accel = std::max(max_accel, a.norm());
    a_prev = a;
  }
  return {max_jump, max_accel};
}

TEST(RouteMotion, AccelerationIsContinuousAndSpeedsInRange) {
  RouteMotionConfig config;
  config.cruise_speed_m_s = 1.3;
  const RouteMotion motion(rectangle_route(), config);
  // Continuous acceleration: its steps shrink with the sampling interval (a jump would not).
  const auto [jump_2ms, max_accel] = acceleration_steps(motion, 2 * kMs);
  const auto [jump_05ms, unused] = acceleration_steps(motion, kMs / 2);
  EXPECT_LT(jump_2ms, 0.05);
  EXPECT_LT(jump_05ms, 0.4 * jump_2ms);
  EXPECT_LT(max_accel, 3.0);  // walking: corners taken at cruise speed stay gentle
  double max_speed = 0, cruise_min = 1e9;
  const TimeNs cruise_begin = motion.start_ns() + s_to_ns(config.rest_start_s + config.ramp_s);
  const TimeNs cruise_end = motion.end_ns() - s_to_ns(config.rest_end_s + config.ramp_s);
  for (TimeNs t = motion.start_ns(); t <= motion.end_ns(); t += 10 * kMs) {
    const double speed = motion.state(t).v_W.norm();
    max_speed = std::max(max_speed, speed);
    if (t > cruise_begin && t < cruise_end) cruise_min = std::min(cruise_min, speed);
  }
  EXPECT_LT(max_speed, 1.3 + 1e-6);
  EXPECT_GT(cruise_min, 1.3 - 1e-6);
}

TEST(RouteMotion, DurationSetsCruiseSpeed) {
  RouteMotionConfig config;
  const RouteMotion probe(rectangle_route(), config);
  config.cruise_speed_m_s = RouteMotion::cruise_speed_for_duration(probe.length_m(), 60.0, config);
  const RouteMotion motion(rectangle_route(), config);
  EXPECT_NEAR(ns_to_s(motion.end_ns() - motion.start_ns()), 60.0, 1e-6);
  EXPECT_THROW(RouteMotion::cruise_speed_for_duration(probe.length_m(), 2.0, config), std::invalid_argument);
}

TEST(RouteMotion, LapsFlyTheSameRouteAgainSmoothly) {
  RouteMotionConfig config;
  const RouteMotion one(rectangle_route(), config);
  config.laps = 2;
  const RouteMotion two(rectangle_route(), config);
  EXPECT_DOUBLE_EQ(two.length_m(), one.length_m());
  // The second lap adds one lap's length at cruise speed.
  EXPECT_NEAR(ns_to_s(two.end_ns() - one.end_ns()), one.length_m() / config.cruise_speed_m_s, 1e-6);
  // Mid-way through the second lap the rig is where it was mid-way through the first, a lap's time earlier.
  const TimeNs lap_ns = two.end_ns() - one.end_ns();
  for (double f : {0.3, 0.55, 0.8}) {
    const TimeNs t = one.start_ns() + static_cast<TimeNs>(f * double(one.end_ns() - one.start_ns()));
    const SE3 first = two.pose(t), second = two.pose(t + lap_ns);
    EXPECT_LT((first.translation() - second.translation()).norm(), 1e-6) << f;
    EXPECT_LT(rotation_angle(first, second), 1e-6) << f;
  }
  // Across the lap boundary the motion stays smooth, and it ends at rest where it started.
  expect_consistent_derivatives(two, 37 * kMs, 1e-4, 1e-3, 1e-4);
  EXPECT_LT((two.pose(two.end_ns()).translation() - two.pose(two.start_ns()).translation()).norm(), 1e-6);
  config.laps = 0;
  EXPECT_THROW(RouteMotion(rectangle_route(), config), std::invalid_argument);
}

TEST(RouteMotion, RejectsOpenRoutes) {
  std::vector<Vec3> open = rectangle_route();
  open.back() = Vec3(1, 1, 1.5);
  EXPECT_THROW(RouteMotion(open, RouteMotionConfig{}), std::invalid_argument);
}

TEST(PoseSplineMotion, ReproducesASmoothMotionFromItsPoses) {
  const RouteMotion truth(rectangle_route(), RouteMotionConfig{});
  Trajectory poses;
  for (TimeNs t = truth.start_ns(); t <= truth.end_ns(); t += 5 * kMs) poses.push_back({t, truth.pose(t)});
  const PoseSplineMotion motion(poses);
  EXPECT_EQ(motion.start_ns(), truth.start_ns());
  for (TimeNs t = truth.start_ns() + 3 * kMs; t < truth.end_ns(); t += 97 * kMs) {
    const MotionState a = motion.state(t), b = truth.state(t);
    ASSERT_LT((a.T_W_I.translation() - b.T_W_I.translation()).norm(), 1e-3);
    ASSERT_LT(rotation_angle(a.T_W_I, b.T_W_I), 1e-3);
    ASSERT_LT((a.v_W - b.v_W).norm(), 0.02);
    ASSERT_LT((a.omega_I - b.omega_I).norm(), 0.05);
  }
  expect_consistent_derivatives(motion, 53 * kMs, 1e-4, 1e-2, 1e-4);
  EXPECT_THROW(PoseSplineMotion(Trajectory(poses.begin(), poses.begin() + 1)), std::invalid_argument);
}

}  // namespace
}  // namespace vilslam::sim
