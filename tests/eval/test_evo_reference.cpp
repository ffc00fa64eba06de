// evo's published figures on KITTI 00 (ORB-SLAM estimate vs ground truth), see ../shared/data/README.md.
#include <gtest/gtest.h>

#include "eval/trajectory_eval.h"
#include "io/trajectory_io.h"
#include "test_util.h"

namespace vilslam::eval {
namespace {

constexpr double kPrintedPrecision = 5e-6;

TEST(EvoReference, Kitti00OrbApeSe3AndRpe10m) {
  VILSLAM_REQUIRE_SHARED_DATA(gt_path, "trajectories/KITTI_00_gt.txt");
  VILSLAM_REQUIRE_SHARED_DATA(est_path, "trajectories/KITTI_00_ORB.txt");
  VILSLAM_REQUIRE_SHARED_DATA(times_path, "trajectories/KITTI_00_gt_times.txt");
  const Trajectory gt = read_trajectory(gt_path, TrajectoryFormat::kKitti, times_path);
  const Trajectory est = read_trajectory(est_path, TrajectoryFormat::kKitti, times_path);
  TrajectoryEvalConfig config;
  config.align = AlignMode::kSe3;
  config.rpe = {10.0, DeltaUnit::kMeters};
  const TrajectoryEvalReport r = evaluate_trajectory(est, gt, config);
  EXPECT_EQ(r.matched_poses, 4541u);
  EXPECT_NEAR(r.ape.trans.rmse, 1.30345, kPrintedPrecision);
  EXPECT_NEAR(r.ape.trans.mean, 1.15700, kPrintedPrecision);
  EXPECT_NEAR(r.ape.trans.median, 1.06562, kPrintedPrecision);
  EXPECT_NEAR(r.ape.trans.max, 3.58795, kPrintedPrecision);
  EXPECT_NEAR(r.rpe.trans.rmse, 0.22626, kPrintedPrecision);
  EXPECT_NEAR(r.rpe.trans.mean, 0.16902, kPrintedPrecision);
}

}  // namespace
}  // namespace vilslam::eval
