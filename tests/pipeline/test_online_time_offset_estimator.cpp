// The online camera-IMU time offset estimator (pipeline/online_time_offset.h) on synthetic rotations with a
// known offset: it answers every update_every_s of camera time from the last online_window_s of intervals only.
#include <gtest/gtest.h>

#include "pipeline/online_time_offset.h"
#include "vio/rotation_recording.h"

namespace vilslam {
namespace {

TEST(OnlineTimeOffsetEstimator, EstimatesOnItsCadenceFromTheLastWindowOnly) {
  const test::RotationRecording r = test::record_rotations(0.007, 1.0, Vec3(0.01, 0.02, -0.01));
  TimeOffsetConfig config;
  config.online_window_s = 10.0;
  config.update_every_s = 5.0;
  OnlineTimeOffsetEstimator estimator(config, r.R_I_C0);
  std::size_t next_imu = 0;
  std::vector<std::pair<TimeNs, TimeOffsetEstimate>> estimates;
  for (const CameraRotation& rotation : r.rotations) {
    // As live: the IMU samples up to the frame's time (plus the largest offset searched) have arrived.
    while (next_imu < r.imu.size() && r.imu[next_imu].t_ns <= rotation.t_b_ns + s_to_ns(config.max_abs_offset_s)) {
      estimator.add_imu(r.imu[next_imu++]);
    }
    if (const auto e = estimator.add_rotation(rotation)) estimates.emplace_back(rotation.t_b_ns, *e);
  }
  // 31 s of frames from 0.1 s: a try every 5 s of camera time, each answered.
  ASSERT_EQ(estimates.size(), 6u);
  for (std::size_t i = 0; i < estimates.size(); ++i) {
    const auto& [t_ns, e] = estimates[i];
    if (i > 0) {
      EXPECT_EQ(t_ns - estimates[i - 1].first, s_to_ns(5.0));
    }
    EXPECT_NEAR(e.offset_s, 0.007, 0.001) << i;  // 0.2 ms from 30 s (vio tests); 5-10 s are noisier
    EXPECT_LE(e.intervals, 201) << i;  // 10 s of 20 Hz intervals, not everything seen so far
  }
  EXPECT_GE(estimates.back().second.intervals, 195);
}

TEST(OnlineTimeOffsetEstimator, StaysSilentWhileTheRigDoesNotTurn) {
  const test::RotationRecording still = test::record_rotations(0.005, 0.01, Vec3::Zero());
  OnlineTimeOffsetEstimator estimator(TimeOffsetConfig{}, still.R_I_C0);
  for (const ImuSample& s : still.imu) estimator.add_imu(s);
  for (const CameraRotation& rotation : still.rotations) EXPECT_FALSE(estimator.add_rotation(rotation));
}

}  // namespace
}  // namespace vilslam
