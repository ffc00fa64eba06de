#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>

#include "io/dataset.h"
#include "io/euroc_tables.h"
#include "sim/sim_config.h"
#include "test_util.h"

namespace vilslam::sim {
namespace {

namespace fs = std::filesystem;

std::string file_bytes(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

// Relative paths of every file under root, sorted.
std::vector<fs::path> files_under(const fs::path& root) {
  std::vector<fs::path> out;
  for (const auto& e : fs::recursive_directory_iterator(root))
    if (e.is_regular_file()) out.push_back(fs::relative(e.path(), root));
  std::sort(out.begin(), out.end());
  return out;
}

std::size_t count_lines(const fs::path& p) {
  const std::string text = file_bytes(p);
  return static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n'));
}

TEST(Simulate, HighbayPreviewIsReadableAndDeterministic) {
  const fs::path dir = test::temp_dir();
  const test::CliResult a = test::run_cli("simulate highbay --preview --seed 5 --report --out " + (dir / "a").string());
  ASSERT_EQ(a.exit_code, 0) << a.output;
  EXPECT_NE(a.output.find("corners/frame"), std::string::npos) << a.output;
  EXPECT_TRUE(fs::exists(dir / "a" / "report.json"));

  const SimConfig config;
  const double preview_s = config.preview_duration_s;
  const auto reader = open_dataset((dir / "a").string());
  const DatasetSummary& s = reader->summary();
  EXPECT_EQ(s.format, "vilslam");
  EXPECT_EQ(s.imu_samples, static_cast<std::size_t>(preview_s * config.imu.noise.rate_hz) + 1);
  EXPECT_EQ(s.groundtruth_poses, s.imu_samples);
  EXPECT_EQ(s.stereo_frames, static_cast<std::size_t>(preview_s * config.camera.rate_hz) + 1);
  EXPECT_EQ(s.lidar_scans, static_cast<std::size_t>(preview_s * config.lidar.rate_hz));
  EXPECT_TRUE(s.problems.empty());
  EXPECT_FALSE(reader->reference_model_path().empty());
  const RigCalibration& calib = reader->calibration();
  EXPECT_EQ(calib.cam0.width_px, 752);
  EXPECT_NEAR(calib.T_C0_C1().translation().x(), 0.3, 1e-9);
  EXPECT_TRUE(calib.has_lidar);

  // The KITTI copy of the scans.
  EXPECT_EQ(files_under(dir / "a" / "kitti" / "velodyne").size(), s.lidar_scans);
  EXPECT_EQ(count_lines(dir / "a" / "kitti" / "poses.txt"), s.lidar_scans);
  EXPECT_EQ(count_lines(dir / "a" / "kitti" / "times.txt"), s.lidar_scans);

  // Same seed, same bytes (report.json only exists in the first run).
  const test::CliResult b = test::run_cli("simulate highbay --preview --seed 5 --out " + (dir / "b").string());
  ASSERT_EQ(b.exit_code, 0) << b.output;
  std::vector<fs::path> files_a = files_under(dir / "a");
  files_a.erase(std::remove(files_a.begin(), files_a.end(), fs::path("report.json")), files_a.end());
  ASSERT_EQ(files_a, files_under(dir / "b"));
  for (const fs::path& f : files_a) ASSERT_EQ(file_bytes(dir / "a" / f), file_bytes(dir / "b" / f)) << f;

  // An existing output is not replaced without --overwrite.
  const test::CliResult again = test::run_cli("simulate highbay --preview --seed 5 --out " + (dir / "b").string());
  EXPECT_EQ(again.exit_code, 2) << again.output;
}

TEST(Simulate, EurocFlightKeepsTheRealImuTimestamps) {
  VILSLAM_REQUIRE_SHARED_DATA(mav0, "euroc/V1_01_easy_micro/mav0");
  const std::string gt = mav0 + "/state_groundtruth_estimate0/groundtruth.tum";
  const std::string imu = mav0 + "/imu0/data.csv";
  const fs::path out = test::temp_dir() / "flight";
  const test::CliResult r =
      test::run_cli("simulate room --preview --trajectory " + gt + " --imu " + imu + " --out " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;

  const auto reader = open_dataset(out.string());
  std::vector<TimeNs> written;
  while (auto e = reader->next())
    if (const auto* s = std::get_if<ImuSample>(&e->data)) written.push_back(s->t_ns);
  ASSERT_GT(written.size(), 100u);
  // Exactly the real samples inside the written span, with their own timestamps and values.
  std::vector<TimeNs> real;
  for (const ImuSample& s : read_imu_csv(imu))
    if (s.t_ns >= written.front() && s.t_ns <= written.back()) real.push_back(s.t_ns);
  EXPECT_EQ(written, real);
  // The span starts where the ground truth starts (the first sample at or after it).
  EXPECT_LE(std::abs(written.front() - reader->groundtruth().front().t_ns), 5'000'000);
  EXPECT_EQ(reader->groundtruth().size(), written.size());
  // The rig's IMU noise is the real stream's (sim/imu_stream_noise.h), not the simulator's datasheet.
  EXPECT_GT(reader->calibration().imu.accel_noise_density, 2 * ImuNoise{}.accel_noise_density);
}

TEST(Simulate, EurocFlightCutToItsFirstSeconds) {
  VILSLAM_REQUIRE_SHARED_DATA(mav0, "euroc/V1_01_easy_micro/mav0");
  const std::string gt = mav0 + "/state_groundtruth_estimate0/groundtruth.tum";
  const std::string imu = mav0 + "/imu0/data.csv";
  const fs::path out = test::temp_dir() / "flight";
  const test::CliResult r = test::run_cli("simulate room --duration 1 --trajectory " + gt + " --imu " + imu +
                                          " --out " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto reader = open_dataset(out.string());
  const std::vector<GroundTruthState>& truth = reader->groundtruth();
  ASSERT_GT(truth.size(), 100u);
  EXPECT_NEAR(ns_to_s(truth.back().t_ns - truth.front().t_ns), 1.0, 0.02);
  EXPECT_EQ(reader->summary().stereo_frames, 20u);
  // A cut that leaves fewer than two poses is refused, naming the trajectory.
  const test::CliResult none = test::run_cli("simulate room --duration 0.001 --trajectory " + gt + " --imu " + imu +
                                             " --out " + (test::temp_dir() / "none").string());
  EXPECT_EQ(none.exit_code, 2) << none.output;
  EXPECT_NE(none.output.find("within --duration"), std::string::npos) << none.output;
}

TEST(Simulate, BadInputExitsWithCode2) {
  const fs::path dir = test::temp_dir();
  EXPECT_EQ(test::run_cli("simulate nowhere --out " + (dir / "x").string()).exit_code, 2);
  EXPECT_EQ(test::run_cli("simulate highbay --duration 3 --out " + (dir / "x").string()).exit_code, 2);
  EXPECT_EQ(test::run_cli("simulate highbay --imu /nonexistent.csv --out " + (dir / "x").string()).exit_code, 2);
  EXPECT_EQ(test::run_cli("simulate room --trajectory /nonexistent.tum --out " + (dir / "x").string()).exit_code, 2);
  const fs::path bad = dir / "bad.tum";
  std::ofstream(bad) << "0.0 0 0 0 0 0 0 1\nnot a pose\n";
  const test::CliResult r = test::run_cli("simulate room --preview --trajectory " + bad.string() + " --out " +
                                          (dir / "x").string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_FALSE(fs::exists(dir / "x"));
  const fs::path cfg = dir / "bad.yaml";
  std::ofstream(cfg) << "camera: {fx: -3}\n";
  EXPECT_EQ(test::run_cli("simulate highbay --preview --config " + cfg.string() + " --out " + (dir / "y").string())
                .exit_code,
            2);
}

}  // namespace
}  // namespace vilslam::sim
