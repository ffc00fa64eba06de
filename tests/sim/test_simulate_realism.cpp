// Sensor realism reaches the data and never the calibration: the same preview simulated with and without
// --ideal-sensors writes the same calibration files, while the sweeps lose echoes and the stamps move. The true
// mounts are written as ground truth, and the LiDAR-frame ground truth goes through them.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "common/error.h"
#include "io/dataset.h"
#include "io/dataset_groundtruth.h"
#include "io/groundtruth_mounts.h"
#include "test_util.h"

namespace vilslam::sim {
namespace {

namespace fs = std::filesystem;

struct Streams {
  std::size_t lidar_points = 0;
  std::vector<TimeNs> frame_stamps, scan_stamps;
};

Streams read_streams(const fs::path& dir) {
  Streams s;
  const auto reader = open_dataset(dir.string());
  while (auto e = reader->next()) {
    if (const auto* f = std::get_if<StereoFrame>(&e->data)) s.frame_stamps.push_back(f->t_ns);
    if (const auto* l = std::get_if<LidarScan>(&e->data)) {
      s.lidar_points += l->points.size();
      s.scan_stamps.push_back(l->t_ns);
    }
  }
  return s;
}

TEST(SimulateRealism, ReachesTheDataAndNotTheCalibration) {
  const fs::path dir = test::temp_dir();
  const fs::path cfg = dir / "small.yaml";
  std::ofstream(cfg) << "camera: {width_px: 188, height_px: 120, fx: 115, fy: 115, cx: 93.5, cy: 59.5}\n"
                        "preview_duration_s: 0.6\n";
  const std::string common = "simulate outdoor --preview --seed 4 --config " + cfg.string() + " --out ";
  ASSERT_EQ(test::run_cli(common + (dir / "ideal").string() + " --ideal-sensors").exit_code, 0);
  ASSERT_EQ(test::run_cli(common + (dir / "real").string()).exit_code, 0);
  for (const char* file : {"rig.yaml", "mav0/cam0/sensor.yaml", "mav0/cam1/sensor.yaml", "mav0/imu0/sensor.yaml",
                           "mav0/lidar0/sensor.yaml", "groundtruth.tum"})
    EXPECT_EQ(test::read_file_bytes(dir / "ideal" / file), test::read_file_bytes(dir / "real" / file)) << file;
  // The IMU is not its data sheet: other noise and axis errors in the samples, the same noise in the calibration.
  EXPECT_NE(test::read_file_bytes(dir / "ideal" / "mav0/imu0/data.csv"),
            test::read_file_bytes(dir / "real" / "mav0/imu0/data.csv"));
  const Streams ideal = read_streams(dir / "ideal"), real = read_streams(dir / "real");
  ASSERT_EQ(ideal.frame_stamps.size(), real.frame_stamps.size());
  ASSERT_EQ(ideal.scan_stamps.size(), real.scan_stamps.size());
  for (std::size_t i = 0; i < ideal.frame_stamps.size(); ++i)
    EXPECT_EQ(real.frame_stamps[i] - ideal.frame_stamps[i], 3'000'000);  // the camera's 3 ms
  for (std::size_t i = 0; i < ideal.scan_stamps.size(); ++i)
    EXPECT_EQ(real.scan_stamps[i] - ideal.scan_stamps[i], -2'000'000);   // the LiDAR's -2 ms
  // Missed echoes outweigh nothing else: fewer points, but most of them still there.
  EXPECT_LT(real.lidar_points, ideal.lidar_points * 99 / 100) << ideal.lidar_points << " -> " << real.lidar_points;
  EXPECT_GT(real.lidar_points, ideal.lidar_points / 2);
  std::printf("[realism] outdoor preview: %zu -> %zu LiDAR points (%.1f %% missed)\n", ideal.lidar_points,
              real.lidar_points, 100.0 * (1.0 - double(real.lidar_points) / ideal.lidar_points));

  // Ground truth only: the true mounts, 0.5 deg and 1 cm off the nominal ones, and the LiDAR-frame ground truth
  // through the true LiDAR mount. The ideal dataset has no such file and keeps the nominal mount.
  EXPECT_FALSE(read_groundtruth_mounts((dir / "ideal").string()));
  const std::optional<GroundTruthMounts> mounts = read_groundtruth_mounts((dir / "real").string());
  ASSERT_TRUE(mounts);
  const RigCalibration nominal = open_dataset((dir / "real").string())->calibration();
  for (const auto& [true_T, nominal_T] : {std::pair{mounts->T_I_C0, nominal.T_I_C0}, {mounts->T_I_L, nominal.T_I_L}}) {
    const SE3 error = nominal_T.inverse() * true_T;
    EXPECT_NEAR(so3::log(error.rotation()).norm(), 0.5 * M_PI / 180, 1e-9);
    EXPECT_NEAR(error.translation().norm(), 0.01, 0.002);
  }
  const Trajectory gt_I = dataset_groundtruth((dir / "real").string(), GroundTruthFrame::kImu);
  const Trajectory gt_L = dataset_groundtruth((dir / "real").string(), GroundTruthFrame::kLidar);
  ASSERT_EQ(gt_I.size(), gt_L.size());
  const SE3 T_I_L = gt_I.back().T_W_B.inverse() * gt_L.back().T_W_B;
  EXPECT_LT((T_I_L.translation() - mounts->T_I_L.translation()).norm(), 1e-9);
  EXPECT_LT(so3::log(T_I_L.rotation().transpose() * mounts->T_I_L.rotation()).norm(), 1e-9);
}

// Issue 61: the estimator's calibration depends on the seed and the data sheet, never on what the simulator drew.
// The same seed with other drawn IMU noise (every factor 2.5 instead of one drawn in [0.5, 3]) and other axis
// errors writes other samples and the same calibration, byte for byte.
TEST(SimulateRealism, OtherDrawnImuErrorsLeaveTheCalibrationAsItWas) {
  const fs::path dir = test::temp_dir();
  const std::string small = "camera: {width_px: 188, height_px: 120, fx: 115, fy: 115, cx: 93.5, cy: 59.5}\n"
                            "preview_duration_s: 0.6\n";
  std::ofstream(dir / "drawn.yaml") << small;
  std::ofstream(dir / "other.yaml") << small
                                    << "imu: {min_noise_factor: 2.5, max_noise_factor: 2.5, max_scale_error: 0.004, "
                                       "max_misalignment_deg: 0.1, max_g_sensitivity: 5.0e-5}\n";
  for (const char* name : {"drawn", "other"}) {
    const test::CliResult sim = test::run_cli("simulate room --preview --seed 4 --config " +
                                              (dir / (std::string(name) + ".yaml")).string() + " --out " +
                                              (dir / name).string());
    ASSERT_EQ(sim.exit_code, 0) << sim.output;
  }
  for (const char* file : {"rig.yaml", "mav0/imu0/sensor.yaml", "mav0/cam0/sensor.yaml", "mav0/lidar0/sensor.yaml"})
    EXPECT_EQ(test::read_file_bytes(dir / "drawn" / file), test::read_file_bytes(dir / "other" / file)) << file;
  EXPECT_NE(test::read_file_bytes(dir / "drawn" / "mav0/imu0/data.csv"),
            test::read_file_bytes(dir / "other" / "mav0/imu0/data.csv"));
}

TEST(GroundTruthMounts, AnUnreadableFileIsAnErrorNamingIt) {
  const fs::path dir = test::temp_dir();
  fs::create_directories(dir / "mav0/state_groundtruth_estimate0");
  std::ofstream(dir / kGroundTruthMountsFile) << "T_I_C0: [1, 0, 0]\n";
  try {
    read_groundtruth_mounts(dir.string());
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("sensor_mounts.yaml"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace vilslam::sim
