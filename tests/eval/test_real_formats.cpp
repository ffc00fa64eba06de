// Cross-format evaluation on real data: the EuRoC V1_02 ground truth in EuRoC csv (40 Hz subset) against the
// same ground truth in TUM format (200 Hz): association must pair every csv pose with its TUM twin.
#include <gtest/gtest.h>

#include "eval/trajectory_eval.h"
#include "io/trajectory_io.h"
#include "test_util.h"

namespace vilslam::eval {
namespace {

TEST(RealFormats, EurocCsvAgainstTumOfTheSameGroundTruth) {
  VILSLAM_REQUIRE_SHARED_DATA(csv, "euroc/V1_02_medium_imu/mav0/gt0/data.csv");
  VILSLAM_REQUIRE_SHARED_DATA(tum, "euroc/groundtruth/V1_02_medium.txt");
  const Trajectory est = read_trajectory(csv, detect_trajectory_format(csv));
  const Trajectory gt = read_trajectory(tum, detect_trajectory_format(tum));
  ASSERT_EQ(est.size(), 3340u);
  TrajectoryEvalConfig config;
  config.align = AlignMode::kNone;
  config.max_diff_ns = 1'000'000;  // 1 ms: the twins differ only by the TUM file's 10 us time rounding
  const TrajectoryEvalReport r = evaluate_trajectory(est, gt, config);
  EXPECT_EQ(r.matched_poses, est.size());
  EXPECT_LT(r.ape.trans.max, 1e-5);  // both files print 6 decimals
  EXPECT_LT(r.ape.rot.max, 1e-3);
  EXPECT_LT(r.rpe.trans.max, 2e-5);
}

}  // namespace
}  // namespace vilslam::eval
