// `vilslam calibrate-lidar`: the refined mount written as the dataset's calibration, read back by `--calib`;
// bad input gives exit code 2 and no file.
#include <gtest/gtest.h>

#include <filesystem>

#include "calib/turning_route.h"
#include "io/calibration_io.h"
#include "io/dataset.h"
#include "io/synthetic_dataset.h"
#include "io/trajectory_io.h"
#include "test_util.h"

namespace vilslam {
namespace {

using calib::test::kDeg;

struct Files {
  std::filesystem::path dir, data, lidar, out;
};

// The synthetic dataset (its nominal LiDAR mount) with `rig`'s gyroscope as its IMU stream, and the LiDAR's
// poses on that route with the mount off by `correction` (in L).
Files write_inputs(const calib::test::TurningRig& rig, const Vec3& correction) {
  Files f;
  f.dir = vilslam::test::temp_dir();
  f.data = f.dir / "data";
  f.lidar = f.dir / "lidar.tum";
  f.out = f.dir / "refined.rig.yaml";
  vilslam::test::SyntheticData data = vilslam::test::make_synthetic_data();
  const TimeNs t0 = data.imu.front().t_ns;
  data.imu = rig.imu;
  for (ImuSample& s : data.imu) s.t_ns += t0;
  Trajectory T_W_I = rig.T_W_I;
  for (TimedPose& p : T_W_I) p.t_ns += t0;
  vilslam::test::write_synthetic_dataset(f.data.string(), data);
  const Mat3 R_true = data.calib.T_I_L.rotation() * so3::exp(correction);
  write_trajectory(f.lidar.string(), calib::test::lidar_route(T_W_I, R_true, 0.03 * kDeg, 11), TrajectoryFormat::kTum);
  return f;
}

std::string args(const Files& f) {
  return "calibrate-lidar " + f.data.string() + " --lidar-poses " + f.lidar.string() + " --out " + f.out.string();
}

TEST(CmdCalibrateLidar, WritesTheDatasetsCalibrationWithTheMountsTiltCorrected) {
  const Vec3 correction = Vec3(0.5, -0.2, 0.3) * kDeg;
  const Files f = write_inputs(calib::test::turning_rig(0.0, Vec3(0.003, -0.002, 0.001)), correction);
  const vilslam::test::CliResult r = vilslam::test::run_cli(args(f));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("directions estimated: 2 of 3"), std::string::npos) << r.output;
  const RigCalibration nominal = vilslam::test::synthetic_calibration();
  const RigCalibration refined = read_rig_yaml(f.out.string());
  const Vec3 estimated = so3::log(nominal.T_I_L.rotation().transpose() * refined.T_I_L.rotation());
  // The synthetic mount is turned 3.1 rad about I's z, so L's z is the turns' axis: its tilt is seen, its yaw kept.
  EXPECT_NEAR(estimated.x(), correction.x(), 0.02 * kDeg);
  EXPECT_NEAR(estimated.y(), correction.y(), 0.02 * kDeg);
  EXPECT_LT(std::abs(estimated.z()), 0.01 * kDeg);
  EXPECT_LT((refined.T_I_L.translation() - nominal.T_I_L.translation()).norm(), 1e-12);
  EXPECT_LT((refined.T_I_C0.matrix() - nominal.T_I_C0.matrix()).norm(), 1e-9);
  // `--calib` hands it to any dataset, a folder too.
  DatasetOptions options;
  options.calibration_path = f.out.string();
  const auto reader = open_dataset(f.data.string(), options);
  EXPECT_LT((reader->calibration().T_I_L.matrix() - refined.T_I_L.matrix()).norm(), 1e-12);
  EXPECT_EQ(reader->summary().calibration, "file " + f.out.string());
  EXPECT_GT((open_dataset(f.data.string())->calibration().T_I_L.matrix() - refined.T_I_L.matrix()).norm(), 1e-3);
}

TEST(CmdCalibrateLidar, ARouteWithoutTurnsIsAnErrorAndWritesNothing) {
  calib::test::TurningRig straight;
  for (int k = 0; k <= 6000; ++k) {
    ImuSample s;
    s.t_ns = static_cast<TimeNs>(k) * 5'000'000;
    straight.imu.push_back(s);
    if (k % 20 == 0) straight.T_W_I.push_back({s.t_ns, SE3(Mat3::Identity(), Vec3(0.005 * k, 0.0, 0.0))});
  }
  const Files f = write_inputs(straight, Vec3(0.5, 0.0, 0.0) * kDeg);
  const vilslam::test::CliResult r = vilslam::test::run_cli(args(f));
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("turns too little"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find(f.lidar.string()), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(f.out));
}

TEST(CmdCalibrateLidar, MissingOrUnorderedPosesAreErrorsNamingTheFile) {
  const Files f = write_inputs(calib::test::turning_rig(0.0), Vec3::Zero());
  const Trajectory lidar = read_trajectory(f.lidar.string(), TrajectoryFormat::kTum);
  std::filesystem::remove(f.lidar);
  vilslam::test::CliResult r = vilslam::test::run_cli(args(f));
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find(f.lidar.string()), std::string::npos) << r.output;
  Trajectory backwards = lidar;
  std::swap(backwards[10], backwards[11]);
  write_trajectory(f.lidar.string(), backwards, TrajectoryFormat::kTum);
  r = vilslam::test::run_cli(args(f));
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find(f.lidar.string()), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(f.out));
}

}  // namespace
}  // namespace vilslam
