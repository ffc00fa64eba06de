#include <gtest/gtest.h>

#include <filesystem>
#include <random>

#include "io/euroc_tables.h"
#include "io/trajectory_io.h"
#include "sim/imu_alignment.h"
#include "sim/trajectory.h"
#include "test_util.h"

namespace vilslam::sim {
namespace {

namespace fs = std::filesystem;
constexpr double kDeg = M_PI / 180;

// Every file of a dataset the estimator reads its calibration from: noise densities, extrinsics, time
// offsets, intrinsics.
const char* const kCalibrationFiles[] = {"rig.yaml",
                                         "mav0/imu0/sensor.yaml",
                                         "mav0/cam0/sensor.yaml",
                                         "mav0/cam1/sensor.yaml",
                                         "mav0/lidar0/sensor.yaml",
                                         "kitti/calib.txt"};

// The ground truth with 1 mm Gaussian noise on every position and 0.05 deg on every attitude (per axis).
Trajectory perturbed(Trajectory poses) {
  std::mt19937_64 rng(11);
  std::normal_distribution<double> n01;
  const auto draw = [&] { return Vec3(n01(rng), n01(rng), n01(rng)); };
  for (TimedPose& p : poses) {
    const Vec3 dp_m = 1e-3 * draw();
    const Vec3 dr_rad = 0.05 * kDeg * draw();
    p.T_W_B = SE3(p.T_W_B.rotation() * so3::exp(dr_rad), p.T_W_B.translation() + dp_m);
  }
  return poses;
}

// Issue 11, must-show 1: the calibration written for a real-IMU flight depends on the IMU stream and the
// config only. The same flight over a perturbed ground truth renders other images and ground truth but
// writes byte-identical calibration files, while a calibration fitted against the ground truth (the
// alignment's residuals, the former noise source) would have changed.
TEST(SimulateCalibration, RealImuFlightCalibrationDoesNotDependOnTheGroundTruth) {
  VILSLAM_REQUIRE_SHARED_DATA(mav0, "euroc/V1_01_easy_micro/mav0");
  const std::string gt = mav0 + "/state_groundtruth_estimate0/groundtruth.tum";
  const std::string imu = mav0 + "/imu0/data.csv";
  const fs::path dir = test::temp_dir();
  const Trajectory original = read_trajectory(gt, TrajectoryFormat::kTum);
  const Trajectory noisy = perturbed(original);
  write_trajectory((dir / "perturbed.tum").string(), noisy, TrajectoryFormat::kTum);

  for (const auto& [name, path] : {std::pair{"a", gt}, std::pair{"b", (dir / "perturbed.tum").string()}}) {
    const test::CliResult r = test::run_cli("simulate room --preview --trajectory " + path + " --imu " + imu +
                                            " --out " + (dir / name).string());
    ASSERT_EQ(r.exit_code, 0) << r.output;
  }
  for (const char* file : kCalibrationFiles) {
    const std::string a = test::read_file_bytes(dir / "a" / file);
    ASSERT_FALSE(a.empty()) << file;
    EXPECT_EQ(a, test::read_file_bytes(dir / "b" / file)) << file;
  }
  EXPECT_EQ(test::read_file_bytes(dir / "a/mav0/imu0/data.csv"), test::read_file_bytes(dir / "b/mav0/imu0/data.csv"));
  // The perturbation reached the simulator: the ground truth it wrote differs.
  EXPECT_NE(test::read_file_bytes(dir / "a/groundtruth.tum"), test::read_file_bytes(dir / "b/groundtruth.tum"));

  // A ground-truth-fitted calibration would not have passed: the residual RMS over the same samples moves.
  const std::vector<ImuSample> samples = read_imu_csv((dir / "a/mav0/imu0/data.csv").string());
  const ImuAlignment fit_a = align_imu_to_motion(PoseSplineMotion(original), samples);
  const ImuAlignment fit_b = align_imu_to_motion(PoseSplineMotion(noisy), samples);
  EXPECT_NE(fit_a.gyro_rms_rad_s, fit_b.gyro_rms_rad_s);
  EXPECT_NE(fit_a.accel_rms_m_s2, fit_b.accel_rms_m_s2);
}

}  // namespace
}  // namespace vilslam::sim
