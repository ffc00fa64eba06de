// The Vio on EuRoC V1_02_medium's real motion: the ground truth is fitted by the simulator's pose spline,
// the IMU is simulated from it with noise and random-walk biases (sim/imu_sim), and the stereo matches
// are synthetic landmarks on the walls of a room around the flight seen with EuRoC's camera extrinsics.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <random>
#include <set>

#include "analytic_motion.h"
#include "io/dataset.h"
#include "sim/imu_sim.h"
#include "sim/trajectory.h"
#include "test_util.h"
#include "vio/vio.h"

namespace vilslam {
namespace {

// Points on the six faces of the box around the positions, 1 m margin.
std::vector<Vec3> room_landmarks(const Trajectory& traj, int count, std::uint32_t seed) {
  Vec3 lo = Vec3::Constant(1e9), hi = Vec3::Constant(-1e9);
  for (const TimedPose& p : traj) {
    lo = lo.cwiseMin(p.T_W_B.translation());
    hi = hi.cwiseMax(p.T_W_B.translation());
  }
  lo -= Vec3::Constant(2.0);
  hi += Vec3::Constant(2.0);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<Vec3> pts;
  for (int i = 0; i < count; ++i) {
    Vec3 p = lo + Vec3(u(rng), u(rng), u(rng)).cwiseProduct(hi - lo);
    const int face = i % 6;
    p[face / 2] = face % 2 ? hi[face / 2] : lo[face / 2];
    pts.push_back(p);
  }
  return pts;
}

TEST(VioEurocMotion, FollowsV102WithSimulatedSensors) {
  VILSLAM_REQUIRE_SHARED_DATA(gt_path, "euroc/V1_02_medium_imu");
  VILSLAM_REQUIRE_SHARED_DATA(calib_path, "euroc/V1_01_easy_micro");
  const std::vector<GroundTruthState> gt = open_dataset(gt_path)->groundtruth();
  RigCalibration calib = open_dataset(calib_path)->calibration();
  Trajectory traj;
  for (const GroundTruthState& g : gt) traj.push_back({g.t_ns, g.T_W_I});
  const sim::PoseSplineMotion motion(traj);

  sim::ImuSimConfig imu_config;
  imu_config.noise = calib.imu;
  imu_config.seed = 3;
  const double duration_s = 20.0;
  const TimeNs t_start = motion.start_ns();
  const TimeNs t_end = t_start + s_to_ns(duration_s);
  const sim::ImuSimulation imu = sim::simulate_imu(motion, imu_config, t_start, t_end);

  const StereoExtrinsics extr{calib.T_I_C0, calib.T_I_C1};
  const std::vector<Vec3> landmarks = room_landmarks(traj, 3000, 5);
  const double fx = calib.cam0.fx;
  std::mt19937 rng(5);
  Vio vio(calib);
  const TimeNs frame_period = kNsPerSecond / 10;
  TimeNs next_frame = t_start + kNsPerSecond;  // one second of IMU before the first frame
  std::set<std::uint64_t> tracked;
  SE3 T_gt_vio;
  bool aligned = false;
  double max_error = 0, final_error = 0, path_m = 0;
  Vec3 last_p = motion.pose(next_frame).translation();
  int frames = 0;
  for (const ImuSample& s : imu.samples) {
    vio.add_imu(s);
    if (s.t_ns < next_frame) continue;
    const sim::MotionState truth_motion = motion.state(s.t_ns);
    NavState truth;
    truth.t_ns = s.t_ns;
    truth.R_W_I = truth_motion.T_W_I.rotation();
    truth.p_W_I = truth_motion.T_W_I.translation();
    // Up to 150 matches a frame, tracked ones first, like the frontend.
    FrontendOutput all = test::observe(truth, landmarks, extr, 0.7 / fx, rng);
    FrontendOutput frame;
    frame.t_ns = s.t_ns;
    std::stable_partition(all.matches.begin(), all.matches.end(),
                          [&](const StereoMatch& m) { return tracked.count(m.track_id) > 0; });
    tracked.clear();
    for (const StereoMatch& m : all.matches) {
      if (frame.matches.size() >= 150) break;
      if (std::abs(m.left_norm.y()) > 0.52 || std::abs(m.right_norm.y()) > 0.52) continue;
      frame.matches.push_back(m);
      tracked.insert(m.track_id);
    }
    vio.add_frame(frame);
    ++frames;
    const SE3 est = vio.latest_state()->state.T_W_I();
    if (!aligned) {  // VIO's yaw and position are a gauge: align at the first frame
      T_gt_vio = truth_motion.T_W_I * est.inverse();
      aligned = true;
    }
    final_error = ((T_gt_vio * est).translation() - truth.p_W_I).norm();
    max_error = std::max(max_error, final_error);
    path_m += (truth.p_W_I - last_p).norm();
    last_p = truth.p_W_I;
    next_frame += frame_period;
  }
  std::printf("V1_02 motion, %.0f s, %d frames, path %.2f m: max position error %.3f m, final %.3f m (%.2f %%)\n",
              duration_s, frames, path_m, max_error, final_error, 100.0 * final_error / path_m);
  EXPECT_GT(path_m, 5.0);
  EXPECT_LT(final_error, 0.02 * path_m);
}

}  // namespace
}  // namespace vilslam
