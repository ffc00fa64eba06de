// The offline pipeline on the real EuRoC V1_01 slice (the MAV is almost still for its 4.7 s).
#include <gtest/gtest.h>

#include "io/dataset.h"
#include "pipeline/offline_runner.h"
#include "pipeline/timing_stats.h"
#include "test_util.h"

namespace vilslam {
namespace {

TEST(OfflineRunner, EurocSliceInitializesAndStaysStill) {
  VILSLAM_REQUIRE_SHARED_DATA(path, "euroc/V1_01_easy_micro");
  const auto reader = open_dataset(path);
  const OfflineRunResult r = run_offline(*reader, OfflineRunConfig{});

  ASSERT_EQ(r.matches_per_frame.size(), reader->summary().stereo_frames);
  for (std::size_t i = 0; i < r.matches_per_frame.size(); ++i) {
    EXPECT_GE(r.matches_per_frame[i], 100) << "frame " << i;
  }
  // Every frame after the first IMU sample becomes a state.
  ASSERT_GE(r.camera_states.size(), r.matches_per_frame.size() - 1);
  const Vec3 p0 = r.camera_states.front().T_W_B.translation();
  double max_offset_m = 0;
  for (const TimedPose& s : r.camera_states) max_offset_m = std::max(max_offset_m, (s.T_W_B.translation() - p0).norm());
  for (const TimedPose& s : r.imu_poses) max_offset_m = std::max(max_offset_m, (s.T_W_B.translation() - p0).norm());
  std::printf("max distance from the start over the slice: %.4f m\n", max_offset_m);
  EXPECT_LT(max_offset_m, 0.05);

  // IMU-rate poses cover the camera-rate states and stop just after the last frame.
  ASSERT_FALSE(r.imu_poses.empty());
  EXPECT_GT(r.imu_poses.size(), 3 * r.camera_states.size());
  EXPECT_LE(r.imu_poses.back().t_ns - r.camera_states.back().t_ns, 10'000'000);
  EXPECT_EQ(r.frontend_ms.size(), r.matches_per_frame.size());
  EXPECT_EQ(r.smoother_ms.size(), r.matches_per_frame.size());

  // The time read covers every state and no more than the dataset; the wall time is measured.
  const DatasetSummary& summary = reader->summary();
  EXPECT_GE(r.data_s, ns_to_s(r.camera_states.back().t_ns - r.camera_states.front().t_ns));
  EXPECT_LE(r.data_s, ns_to_s(summary.end_t_ns - summary.start_t_ns));
  EXPECT_GT(r.run_wall_s, 0.0);
}

TEST(TimingStats, NearestRankPercentiles) {
  std::vector<double> ms;
  for (int i = 100; i >= 1; --i) ms.push_back(i);
  const TimingSummary s = summarize_timings(ms);
  EXPECT_EQ(s.count, 100u);
  EXPECT_DOUBLE_EQ(s.median_ms, 50);
  EXPECT_DOUBLE_EQ(s.p95_ms, 95);
  EXPECT_DOUBLE_EQ(s.max_ms, 100);
  EXPECT_EQ(summarize_timings({}).count, 0u);
}

}  // namespace
}  // namespace vilslam
