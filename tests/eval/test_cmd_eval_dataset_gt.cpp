// `vilslam eval --gt DATASET --gt-frame imu|lidar` and `eval-loops --gt DATASET`: a dataset's ground truth
// in the IMU or the LiDAR frame (T_W_I T_I_L with the rig's extrinsic).
#include <gtest/gtest.h>

#include "io/synthetic_dataset.h"
#include "io/trajectory_io.h"
#include "test_util.h"

namespace vilslam {
namespace {

// The APE RMSE line of `vilslam eval`.
double ape_rmse(const std::string& output) {
  const std::size_t at = output.find("APE [m]");
  return at == std::string::npos ? -1.0 : std::stod(output.substr(at + 7));
}

TEST(CmdEvalDatasetGt, LidarFrameGroundTruthOfADataset) {
  const auto dir = test::temp_dir();
  const test::SyntheticData data = test::make_synthetic_data();
  test::write_synthetic_dataset((dir / "data").string(), data);
  Trajectory lidar_poses;
  for (const GroundTruthState& g : data.groundtruth) lidar_poses.push_back({g.t_ns, g.T_W_I * data.calib.T_I_L});
  write_trajectory((dir / "lidar.tum").string(), lidar_poses, TrajectoryFormat::kTum);
  const std::string base = "eval --align none --est " + (dir / "lidar.tum").string() + " --gt " + (dir / "data").string();
  const test::CliResult lidar = test::run_cli(base + " --gt-frame lidar");
  ASSERT_EQ(lidar.exit_code, 0) << lidar.output;
  EXPECT_LT(ape_rmse(lidar.output), 1e-6) << lidar.output;
  // In the IMU frame the same poses are off by the extrinsic's lever arm (and its rotation about z).
  const test::CliResult imu = test::run_cli(base + " --gt-frame imu");
  ASSERT_EQ(imu.exit_code, 0) << imu.output;
  EXPECT_GT(ape_rmse(imu.output), 0.04) << imu.output;
  const test::CliResult bad = test::run_cli(base + " --gt-frame camera");
  EXPECT_NE(bad.exit_code, 0);
}

}  // namespace
}  // namespace vilslam
