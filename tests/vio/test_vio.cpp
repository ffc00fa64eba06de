// The Vio front door: static initialization, camera-rate states and IMU-rate poses on the analytic motion.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>

#include "analytic_motion.h"
#include "common/error.h"
#include "vio/vio.h"

namespace vilslam {
namespace {

RigCalibration test_calibration() {
  RigCalibration calib;
  const StereoExtrinsics extr = test::test_extrinsics();
  calib.T_I_C0 = extr.T_I_C0;
  calib.T_I_C1 = extr.T_I_C1;
  calib.cam0.fx = calib.cam0.fy = calib.cam1.fx = calib.cam1.fy = 450.0;
  return calib;
}

// Static initialization, then 4 s of the analytic motion with noisy, biased IMU and 10 Hz stereo frames.
struct AnalyticFlight {
  std::vector<VioStateOutput> states;
  std::vector<VioImuOutput> imu_poses;
  std::vector<VioLossEvent> losses;
  double max_frame_error = 0, max_imu_error = 0;  // over the states before the first loss
  Vec3 bg = Vec3::Zero();
};

// gap: IMU samples in [begin, end) s are missing (a stalled driver); frames wait for the next sample, as the
// pipeline hands a frame over once a sample after it arrived.
struct ImuGap {
  double begin_s = -1, end_s = -1;
};

AnalyticFlight fly_analytic_motion(const test::AnalyticMotion& motion, const ImuGap& gap = {},
                                   const VioConfig& config = {}, double duration_s = 5.0) {
  const RigCalibration calib = test_calibration();
  const StereoExtrinsics extr{calib.T_I_C0, calib.T_I_C1};
  const std::vector<Vec3> landmarks = test::test_landmarks(400, 9);
  std::mt19937 rng(9);
  std::normal_distribution<double> gauss(0.0, 1.0);
  AnalyticFlight f;
  f.bg = Vec3(0.004, -0.003, 0.002);
  const Vec3 ba(0.01, -0.01, 0.02);
  const double imu_dt = 1.0 / calib.imu.rate_hz;
  const double sigma_norm = 0.5 / 450.0;

  Vio vio(calib, config);
  vio.on_state([&](const VioStateOutput& s) { f.states.push_back(s); });
  vio.on_imu_pose([&](const VioImuOutput& p) { f.imu_poses.push_back(p); });
  vio.on_lost([&](const VioLossEvent& e) { f.losses.push_back(e); });

  const int imu_per_frame = 20;  // 10 Hz frames at 200 Hz IMU
  std::vector<FrontendOutput> waiting;
  for (int k = 0; k <= std::lround(duration_s * 200); ++k) {
    const double t = k * imu_dt;
    ImuSample s = motion.imu(t);
    s.gyro_rad_s += f.bg + Vec3(gauss(rng), gauss(rng), gauss(rng)) * calib.imu.gyro_noise_density / std::sqrt(imu_dt);
    s.accel_m_s2 += ba + Vec3(gauss(rng), gauss(rng), gauss(rng)) * calib.imu.accel_noise_density / std::sqrt(imu_dt);
    if (k >= 200 && k % imu_per_frame == 0) {  // frames from the end of the rest on
      waiting.push_back(test::observe(motion.state(t), landmarks, extr, sigma_norm, rng));
    }
    if (t >= gap.begin_s && t < gap.end_s) continue;
    vio.add_imu(s);
    if (f.losses.empty() && vio.latest_imu_pose() && vio.latest_imu_pose()->t_ns == s.t_ns) {
      f.max_imu_error = std::max(f.max_imu_error, (vio.latest_imu_pose()->T_W_I.translation() - motion.state(t).p_W_I).norm());
    }
    for (const FrontendOutput& frame : waiting) {
      vio.add_frame(frame);
      if (!f.losses.empty()) continue;
      EXPECT_TRUE(vio.latest_state().has_value());
      const NavState& est = vio.latest_state()->state;
      EXPECT_EQ(est.t_ns, frame.t_ns);
      f.max_frame_error = std::max(f.max_frame_error, (est.p_W_I - motion.state(ns_to_s(frame.t_ns)).p_W_I).norm());
    }
    waiting.clear();
  }
  return f;
}

TEST(Vio, InitializesStaticAndTracksTheMotion) {
  test::AnalyticMotion motion;
  motion.rest_s = 1.0;
  const AnalyticFlight f = fly_analytic_motion(motion);
  const auto& [states, imu_poses, losses, max_frame_error, max_imu_error, bg] = f;
  EXPECT_TRUE(losses.empty());
  std::printf("static init + 4 s of motion: %zu states, %zu IMU-rate poses, max error %.4f m (frames), %.4f m (IMU rate)\n",
              states.size(), imu_poses.size(), max_frame_error, max_imu_error);
  EXPECT_EQ(states.size(), 41u);
  EXPECT_EQ(imu_poses.size(), 800u);  // every sample after the first frame
  EXPECT_LT(max_frame_error, 0.08);
  EXPECT_LT(max_imu_error, 0.08);
  // The gyro bias comes from the static average and is refined; the covariance is a covariance.
  EXPECT_LT((states.back().state.bias_gyro_rad_s - bg).norm(), 2e-3);
  const Eigen::SelfAdjointEigenSolver<Mat15> eig(states.back().covariance);
  EXPECT_GT(eig.eigenvalues().minCoeff(), 0.0);
}

// T_W_I jumps where each new state re-anchors the propagation; T_O_I must follow the true motion from
// sample to sample without those jumps (LiDAR sweeps are dewarped with it).
TEST(Vio, JumpFreeImuMotionFollowsTheTrueMotion) {
  test::AnalyticMotion motion;
  motion.rest_s = 1.0;
  const AnalyticFlight f = fly_analytic_motion(motion);
  ASSERT_GT(f.imu_poses.size(), 100u);
  const auto rotation_error_deg = [&](const SE3& a, const SE3& b, TimeNs ta, TimeNs tb) {
    const Mat3 R_true = motion.state(ns_to_s(ta)).R_W_I.transpose() * motion.state(ns_to_s(tb)).R_W_I;
    const Mat3 R_est = (a.inverse() * b).rotation();
    return Eigen::AngleAxisd(R_true.transpose() * R_est).angle() * 180.0 / M_PI;
  };
  double max_jump_W = 0, max_jump_O = 0;
  for (std::size_t i = 1; i < f.imu_poses.size(); ++i) {
    const VioImuOutput& a = f.imu_poses[i - 1];
    const VioImuOutput& b = f.imu_poses[i];
    max_jump_W = std::max(max_jump_W, rotation_error_deg(a.T_W_I, b.T_W_I, a.t_ns, b.t_ns));
    max_jump_O = std::max(max_jump_O, rotation_error_deg(a.T_O_I, b.T_O_I, a.t_ns, b.t_ns));
  }
  std::printf("largest sample-to-sample rotation error: %.5f deg (T_W_I), %.5f deg (T_O_I)\n", max_jump_W, max_jump_O);
  EXPECT_LT(max_jump_O, 0.2 * max_jump_W);
  EXPECT_LT(max_jump_O, 0.01);
}

// A 0.4 s IMU gap while the rig turns and accelerates: the held measurement across it is a guess, and the
// IMU factor over the gap says so (ImuGapModel), so vision carries the frames in it. Taken at face value (no
// gap model) the same factor pulls the window off the motion.
TEST(Vio, ImuGapIsBridgedByVision) {
  test::AnalyticMotion motion;
  motion.rest_s = 1.0;
  // A shaking rig (periods of 1.5-2 s), so that no interpolation between the samples around the gap is right.
  motion.w_pos = Vec3(3.0, 3.7, 4.1);
  motion.yaw_w = 3.3;
  const ImuGap gap{3.0, 3.4};
  const AnalyticFlight clean = fly_analytic_motion(motion);
  const AnalyticFlight bridged = fly_analytic_motion(motion, gap);
  VioConfig trusting;
  trusting.imu_gap.rate_sigma_rad_s = trusting.imu_gap.accel_sigma_m_s2 = 0.0;
  trusting.loss.enabled = false;  // left to diverge (Vio.DeclaresItselfLostAndStartsAgain catches it)
  const AnalyticFlight trusted = fly_analytic_motion(motion, gap, trusting);
  std::printf("max frame error: no gap %.4f m, gap with the gap model %.4f m, gap taken at face value %.4f m\n",
              clean.max_frame_error, bridged.max_frame_error, trusted.max_frame_error);
  EXPECT_EQ(bridged.states.size(), clean.states.size());
  EXPECT_LT(bridged.max_frame_error, 2.0 * clean.max_frame_error);
  EXPECT_GT(trusted.max_frame_error, 10.0 * bridged.max_frame_error);
}

// The same gap taken at face value, with the loss check on: the window pulled off the images rejects their
// landmarks, the VIO declares itself lost, drops the window and aligns again on the next frames; the restarted
// window follows the motion, continuing from the last trusted state.
TEST(Vio, DeclaresItselfLostAndStartsAgain) {
  test::AnalyticMotion motion;
  motion.rest_s = 1.0;
  motion.w_pos = Vec3(3.0, 3.7, 4.1);
  motion.yaw_w = 3.3;
  VioConfig trusting;
  trusting.imu_gap.rate_sigma_rad_s = trusting.imu_gap.accel_sigma_m_s2 = 0.0;
  const AnalyticFlight f = fly_analytic_motion(motion, {3.0, 3.4}, trusting, 9.0);
  ASSERT_EQ(f.losses.size(), 1u);
  EXPECT_EQ(f.losses[0].reason, VioLoss::kInconsistent);
  EXPECT_GT(ns_to_s(f.losses[0].t_ns), 3.4);
  EXPECT_LT(ns_to_s(f.losses[0].t_ns), 5.0);
  // No state between the loss and the restarted window's first, which comes once the alignment window is full.
  std::size_t first = 0;
  while (first < f.states.size() && !f.states[first].restarted) ++first;
  ASSERT_LT(first, f.states.size());
  EXPECT_EQ(std::count_if(f.states.begin(), f.states.end(), [](const VioStateOutput& s) { return s.restarted; }), 1);
  EXPECT_GT(f.states[first].state.t_ns, f.losses[0].t_ns);
  EXPECT_LT(f.states[first - 1].state.t_ns, f.losses[0].t_ns);
  // After the restart: the motion relative to the restarted window's first state is the true one.
  const NavState& x0 = f.states[first].state;
  const NavState truth0 = motion.state(ns_to_s(x0.t_ns));
  double max_relative_error = 0, restart_jump_m = (x0.p_W_I - truth0.p_W_I).norm();
  for (std::size_t k = first; k < f.states.size(); ++k) {
    const NavState& x = f.states[k].state;
    const NavState truth = motion.state(ns_to_s(x.t_ns));
    const Vec3 est = x0.R_W_I.transpose() * (x.p_W_I - x0.p_W_I);
    const Vec3 tru = truth0.R_W_I.transpose() * (truth.p_W_I - truth0.p_W_I);
    max_relative_error = std::max(max_relative_error, (est - tru).norm());
  }
  const NavState& before = f.states[first - 1].state;
  const double before_error_m = (before.p_W_I - motion.state(ns_to_s(before.t_ns)).p_W_I).norm();
  std::printf("lost at %.2f s, restarted at %.2f s (%zu states after), %.3f m from the truth there (the last state "
              "before: %.3f m); largest error of the motion since then %.4f m\n",
              ns_to_s(f.losses[0].t_ns), ns_to_s(x0.t_ns), f.states.size() - first, restart_jump_m, before_error_m,
              max_relative_error);
  EXPECT_GE(f.states.size() - first, 30u);
  EXPECT_LT(max_relative_error, 0.1);  // at face value the frames err by metres (Vio.ImuGapIsBridgedByVision)
  // The gauge is carried over from the last state published before the loss, so the output does not jump and the
  // divergence before the loss was caught stays in the position (unobservable to the VIO); the restart adds little.
  const double true_step_m = (truth0.p_W_I - motion.state(ns_to_s(before.t_ns)).p_W_I).norm();
  EXPECT_NEAR((x0.p_W_I - before.p_W_I).norm(), true_step_m, 0.1);
  EXPECT_LT(restart_jump_m, before_error_m + 0.25);
}

// A restarted window lost again while its alignment window is replayed (on a simulated tunnel run a 20-state window did
// this): the replay stops publishing (before, it propagated from the dropped window, undefined behaviour that put
// poses 1e29 m away and back in time into the output), and the frames left over start the next alignment.
TEST(Vio, LostAgainWhileReplayingTheAlignmentWindow) {
  test::AnalyticMotion motion;
  motion.rest_s = 1.0;
  VioConfig config;
  config.loss.max_cost_per_landmark = 1e-12;  // every solved state inconsistent: lost on each window's second state
  config.loss.recent_states = config.loss.inconsistent_states = 1;
  const AnalyticFlight f = fly_analytic_motion(motion, {}, config, 9.0);
  ASSERT_GE(f.losses.size(), 3u);  // the static start's, then one inside each replayed alignment window
  ASSERT_FALSE(f.imu_poses.empty());
  double max_error_m = 0;
  for (std::size_t k = 0; k < f.imu_poses.size(); ++k) {
    const VioImuOutput& p = f.imu_poses[k];
    if (k > 0) {
      ASSERT_GT(p.t_ns, f.imu_poses[k - 1].t_ns) << "IMU-rate pose " << k << " goes back in time";
    }
    ASSERT_TRUE(p.T_W_I.translation().allFinite() && p.T_O_I.translation().allFinite());
    max_error_m = std::max(max_error_m, (p.T_W_I.translation() - motion.state(ns_to_s(p.t_ns)).p_W_I).norm());
  }
  for (std::size_t k = 1; k < f.states.size(); ++k) EXPECT_GT(f.states[k].state.t_ns, f.states[k - 1].state.t_ns);
  std::printf("%zu losses, %zu states, %zu IMU-rate poses, farthest %.3f m from the truth\n", f.losses.size(),
              f.states.size(), f.imu_poses.size(), max_error_m);
  EXPECT_LT(max_error_m, 5.0);  // each restart continues from the last published state (its error stays)
}

// Started while moving: the averaged specific force includes the acceleration and the velocity is unknown;
// vision and IMU recover the gravity direction and the speed (both independent of the yaw/position gauge).
TEST(Vio, RecoversFromAMovingStart) {
  const test::AnalyticMotion motion;
  const RigCalibration calib = test_calibration();
  const StereoExtrinsics extr{calib.T_I_C0, calib.T_I_C1};
  const std::vector<Vec3> landmarks = test::test_landmarks(400, 4);
  std::mt19937 rng(4);
  Vio vio(calib);
  double first_gravity_deg = -1, first_speed_error = -1;
  double gravity_deg = 0, speed_error = 0;
  for (int k = 0; k <= 4 * 200; ++k) {
    const double t = 0.5 + k * 0.005;
    vio.add_imu(motion.imu(t));
    if (k < 100 || k % 20 != 0) continue;
    const NavState truth = motion.state(t);
    vio.add_frame(test::observe(truth, landmarks, extr, 0.5 / 450.0, rng));
    const NavState& est = vio.latest_state()->state;
    const Vec3 up_est = est.R_W_I.transpose() * Vec3::UnitZ(), up_true = truth.R_W_I.transpose() * Vec3::UnitZ();
    gravity_deg = std::acos(std::min(1.0, up_est.dot(up_true))) * 180 / M_PI;
    speed_error = std::abs(est.v_W_m_s.norm() - truth.v_W_m_s.norm());
    if (first_gravity_deg < 0) {
      first_gravity_deg = gravity_deg;
      first_speed_error = speed_error;
    }
  }
  std::printf("moving start: gravity direction error %.3f deg -> %.3f deg, speed error %.3f m/s -> %.3f m/s\n",
              first_gravity_deg, gravity_deg, first_speed_error, speed_error);
  EXPECT_GT(first_speed_error, 0.2);
  EXPECT_LT(gravity_deg, 0.5);
  EXPECT_LT(speed_error, 0.03);
}

TEST(Vio, RejectsOutOfOrderInput) {
  Vio vio(test_calibration());
  ImuSample s;
  s.t_ns = 1000;
  s.accel_m_s2 = Vec3(0, 0, 9.81);
  vio.add_imu(s);
  EXPECT_THROW(vio.add_imu(s), InputError);
  s.t_ns = 2000;
  s.gyro_rad_s.x() = std::nan("");
  EXPECT_THROW(vio.add_imu(s), InputError);
  RigCalibration no_camera = test_calibration();
  no_camera.cam0.fx = 0;
  EXPECT_THROW(Vio{no_camera}, InputError);
  FrontendOutput frame;
  frame.t_ns = 1500;
  vio.add_frame(frame);
  EXPECT_TRUE(vio.initialized());
  EXPECT_THROW(vio.add_frame(frame), InputError);
}

TEST(Vio, StaticInitializationLevelsGravity) {
  std::vector<ImuSample> samples;
  const Mat3 R_W_I = so3::exp(Vec3(0.2, -0.1, 0.7));
  for (int k = 0; k < 200; ++k) {
    ImuSample s;
    s.t_ns = k * 5'000'000;
    s.gyro_rad_s = Vec3(0.01, -0.02, 0.005);
    s.accel_m_s2 = R_W_I.transpose() * Vec3(0, 0, 9.81);
    samples.push_back(s);
  }
  const Initialization init = static_initialization(samples, samples.back().t_ns, InitializerConfig{});
  EXPECT_TRUE(init.is_static);
  EXPECT_EQ(init.samples, 200);
  // Gravity direction matches, yaw is zero, gyro bias is the mean rate.
  EXPECT_LT((init.state.R_W_I.transpose() * Vec3::UnitZ() - R_W_I.transpose() * Vec3::UnitZ()).norm(), 1e-9);
  EXPECT_NEAR(so3::yaw_rad(init.state.R_W_I), 0.0, 1e-9);
  EXPECT_LT((init.state.bias_gyro_rad_s - Vec3(0.01, -0.02, 0.005)).norm(), 1e-12);
}

// Turning (a reset while the robot drives a curve): the mean rate is the turn, so the gyro bias starts at 0.
TEST(Vio, MovingInitializationDoesNotTakeTheTurnForABias) {
  std::vector<ImuSample> samples;
  for (int k = 0; k < 200; ++k) {
    ImuSample s;
    s.t_ns = k * 5'000'000;
    s.gyro_rad_s = Vec3(0, 0, 0.3 + 0.2 * std::sin(0.05 * k));  // a yaw rate that changes
    s.accel_m_s2 = Vec3(0.4 * std::cos(0.05 * k), 0.36, 9.81);
    samples.push_back(s);
  }
  const Initialization init = static_initialization(samples, samples.back().t_ns, InitializerConfig{});
  EXPECT_FALSE(init.is_static);
  EXPECT_EQ(init.state.bias_gyro_rad_s, Vec3::Zero());
}

}  // namespace
}  // namespace vilslam
