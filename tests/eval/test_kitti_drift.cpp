#include <gtest/gtest.h>

#include <cmath>

#include "eval/drift.h"
#include "eval/kitti_metric.h"

namespace vilslam::eval {
namespace {

constexpr std::size_t kPoses = 1001;  // 1000 m in 1 m steps

Trajectory line(double step_m) {
  Trajectory traj;
  for (std::size_t i = 0; i < kPoses; ++i) {
    traj.push_back({static_cast<TimeNs>(i), SE3(Quat::Identity(), Vec3(step_m * static_cast<double>(i), 0, 0))});
  }
  return traj;
}

// Mean over all devkit segments of f(L): starts every 10th frame, the segment ends at the first frame
// more than L metres on (here L + 1 frames later), and must lie inside the sequence.
template <class F>
double segment_mean(F f, std::size_t* count) {
  double sum = 0;
  *count = 0;
  for (std::size_t first = 0; first < kPoses; first += 10) {
    for (int L = 100; L <= 800; L += 100) {
      if (first + L + 1 < kPoses) {
        sum += f(L);
        ++*count;
      }
    }
  }
  return sum / static_cast<double>(*count);
}

TEST(KittiMetric, ScaleDriftGivesItsPercentage) {
  const KittiMetric m = compute_kitti_metric(line(1.0), line(1.01));
  std::size_t count = 0;
  const double expected = segment_mean([](int L) { return 0.01 * (L + 1) / L; }, &count);
  EXPECT_EQ(m.segments, count);
  EXPECT_NEAR(m.t_err_percent, 100 * expected, 1e-9);
  EXPECT_NEAR(m.r_err_deg_per_m, 0.0, 1e-9);
  EXPECT_NEAR(m.t_err_percent, 1.0, 0.01);
}

TEST(KittiMetric, HeadingDriftGivesItsRate) {
  const Trajectory gt = line(1.0);
  Trajectory est = gt;
  const double rate_rad = 1e-4;  // per frame, about z
  for (std::size_t i = 0; i < kPoses; ++i) {
    est[i].T_W_B = SE3(so3::exp_quat(Vec3(0, 0, rate_rad * static_cast<double>(i))), gt[i].T_W_B.translation());
  }
  const KittiMetric m = compute_kitti_metric(gt, est);
  std::size_t count = 0;
  const double expected = segment_mean([&](int L) { return rate_rad * (L + 1) / L; }, &count);
  EXPECT_NEAR(m.r_err_deg_per_m, expected * 180 / M_PI, 1e-9);
  EXPECT_GT(m.t_err_percent, 0.0);
}

TEST(KittiMetric, ShortPathHasNoSegment) {
  Trajectory gt = line(1.0);
  gt.resize(90);
  EXPECT_EQ(compute_kitti_metric(gt, gt).segments, 0u);
  EXPECT_EQ(compute_kitti_metric(line(1.0), line(1.0)).t_err_percent, 0.0);
}

Trajectory square_loop(const SE3& T, Vec3 end_offset) {
  const Vec3 corners[] = {{0, 0, 0}, {10, 0, 0}, {10, 10, 0}, {0, 10, 0}, end_offset};
  Trajectory traj;
  TimeNs t = 0;
  for (const Vec3& c : corners) traj.push_back({t++, T * SE3(Quat::Identity(), c)});
  return traj;
}

TEST(FinalDrift, LoopEndDistanceOverPathLength) {
  const SE3 T(so3::exp_quat(Vec3(0.2, 0.1, 1.0)), Vec3(4, 5, 6));
  const Trajectory est = square_loop(T, Vec3(0.4, 0.3, 0));
  const FinalDrift d = final_drift(est);
  const double length = 30 + std::hypot(0.4, 9.7);
  EXPECT_NEAR(d.path_length_m, length, 1e-12);
  EXPECT_NEAR(path_length_m(est), length, 1e-12);
  EXPECT_NEAR(d.drift_m, 0.5, 1e-12);
  EXPECT_NEAR(d.percent, 50.0 / length, 1e-12);
}

TEST(FinalDrift, StartAlignedAgainstGroundTruth) {
  const Trajectory gt = square_loop(SE3(), Vec3::Zero());
  const Trajectory est = square_loop(SE3(so3::exp_quat(Vec3(0, 0, 2.0)), Vec3(4, 5, 6)), Vec3(0.4, 0.3, 0));
  const FinalDrift d = final_drift_start_aligned(gt, est);
  EXPECT_NEAR(d.drift_m, 0.5, 1e-12);
  EXPECT_NEAR(d.path_length_m, 40.0, 1e-12);
  EXPECT_NEAR(d.percent, 1.25, 1e-12);
}

}  // namespace
}  // namespace vilslam::eval
