#include <gtest/gtest.h>

#include <cmath>

#include "eval/ape_rpe.h"

namespace vilslam::eval {
namespace {

SE3 pose(double x, double y, double yaw_deg = 0) {
  return SE3(so3::exp_quat(Vec3(0, 0, yaw_deg * M_PI / 180.0)), Vec3(x, y, 0));
}

// Ground truth: poses 1 m apart along x, no rotation.
Trajectory straight_line(std::size_t n) {
  Trajectory traj;
  for (std::size_t i = 0; i < n; ++i) traj.push_back({static_cast<TimeNs>(i), pose(static_cast<double>(i), 0)});
  return traj;
}

TEST(Stats, MatchesNumpyDefinitions) {
  const ErrorStats s = compute_stats({4, 1, 3, 2});
  EXPECT_DOUBLE_EQ(s.mean, 2.5);
  EXPECT_DOUBLE_EQ(s.median, 2.5);
  EXPECT_DOUBLE_EQ(s.rmse, std::sqrt(7.5));
  EXPECT_DOUBLE_EQ(s.std, std::sqrt(1.25));  // population std (ddof = 0)
  EXPECT_EQ(s.min, 1);
  EXPECT_EQ(s.max, 4);
  EXPECT_DOUBLE_EQ(compute_stats({3, 1, 2}).median, 2);
  EXPECT_DOUBLE_EQ(percentile({1, 2, 3, 4}, 95), 3.85);
  EXPECT_THROW(compute_stats({}), std::invalid_argument);
}

TEST(Ape, TranslationAndRotationParts) {
  const Trajectory gt = straight_line(4);
  Trajectory est = gt;
  est[1].T_W_B = pose(1, 0.3);
  est[2].T_W_B = pose(2, 0, 10);
  const PoseErrors e = compute_ape(gt, est);
  EXPECT_EQ(e.trans_m, (std::vector<double>{0, 0.3, 0, 0}));
  EXPECT_NEAR(e.rot_deg[2], 10.0, 1e-12);
  EXPECT_NEAR(e.rot.max, 10.0, 1e-12);
  EXPECT_NEAR(e.trans.rmse, std::sqrt(0.09 / 4), 1e-15);
}

TEST(Rpe, HandCheckedFramePairs) {
  const Trajectory gt = straight_line(5);
  Trajectory est = gt;
  est[2].T_W_B = pose(2, 0.3);
  est[4].T_W_B = pose(4, 0, 10);  // rotation at the end of a pair does not change its translation
  const RpeConfig config{2, DeltaUnit::kFrames};
  EXPECT_EQ(rpe_pairs(est, config), (std::vector<std::pair<std::size_t, std::size_t>>{{0, 2}, {2, 4}}));
  const PoseErrors e = compute_rpe(gt, est, config);
  ASSERT_EQ(e.trans_m.size(), 2u);
  EXPECT_NEAR(e.trans_m[0], 0.3, 1e-12);  // est moved (2, 0.3) where gt moved (2, 0)
  EXPECT_NEAR(e.trans_m[1], 0.3, 1e-12);  // then (2, -0.3)
  EXPECT_NEAR(e.rot_deg[0], 0.0, 1e-12);
  EXPECT_NEAR(e.rot_deg[1], 10.0, 1e-12);
  EXPECT_NEAR(e.trans.rmse, 0.3, 1e-12);
}

TEST(Rpe, RotationAtPairStartRotatesTheRelativeTranslation) {
  const Trajectory gt = straight_line(3);
  Trajectory est = gt;
  est[1].T_W_B = pose(1, 0, 90);  // heading +y: the next 1 m step along x looks like a step along -y
  const PoseErrors e = compute_rpe(gt, est, {1, DeltaUnit::kFrames});
  EXPECT_NEAR(e.trans_m[1], std::sqrt(2.0), 1e-12);
  EXPECT_NEAR(e.rot_deg[0], 90.0, 1e-12);
  EXPECT_NEAR(e.rot_deg[1], 90.0, 1e-12);
}

TEST(Rpe, MetrePairsFollowAccumulatedPathOfTheEstimate) {
  const Trajectory gt = straight_line(10);
  EXPECT_EQ(rpe_pairs(gt, {2.5, DeltaUnit::kMeters}),
            (std::vector<std::pair<std::size_t, std::size_t>>{{3, 6}, {6, 9}}));
  Trajectory est = gt;
  for (auto& p : est) p.T_W_B.translation() *= 0.5;  // half the path: ids 5, 10 would be needed
  EXPECT_EQ(rpe_pairs(est, {2.0, DeltaUnit::kMeters}), (std::vector<std::pair<std::size_t, std::size_t>>{{4, 8}}));
  const PoseErrors e = compute_rpe(gt, est, {2.0, DeltaUnit::kMeters});
  EXPECT_NEAR(e.trans_m[0], 2.0, 1e-12);  // est moved 2 m where gt moved 4 m
  EXPECT_THROW(compute_rpe(gt, est, {100.0, DeltaUnit::kMeters}), std::invalid_argument);
  EXPECT_THROW(compute_rpe(gt, est, {1.5, DeltaUnit::kFrames}), std::invalid_argument);
}

}  // namespace
}  // namespace vilslam::eval
