#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "io/dataset.h"
#include "test_util.h"

namespace vilslam::sim {
namespace {

namespace fs = std::filesystem;

// A small camera keeps the run cheap; the faults must show in the written streams.
TEST(Simulate, FaultsShowInTheDataset) {
  const fs::path dir = test::temp_dir();
  const fs::path cfg = dir / "faults.yaml";
  std::ofstream(cfg) << "camera: {width_px: 188, height_px: 120, fx: 115, fy: 115, cx: 93.5, cy: 59.5}\n"
                        "preview_duration_s: 1.0\n"
                        "faults:\n"
                        "  camera_blackouts: [[0.2, 0.35]]\n"
                        "  lidar_dropouts: [[0.3, 0.5]]\n"
                        "  imu_gaps: [[0.5, 0.6]]\n"
                        "  exposure_jumps: [[0.7, 0.8]]\n"
                        "sensor_realism: true\n"
                        "calibration_errors:\n"
                        "  camera_time_offset_s: 0.004\n"
                        "  lidar_time_offset_s: -0.002\n";
  const test::CliResult r = test::run_cli("simulate hallway --preview --seed 2 --config " + cfg.string() + " --out " +
                                          (dir / "out").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;

  const auto reader = open_dataset((dir / "out").string());
  const TimeNs t0 = reader->groundtruth().front().t_ns;
  std::size_t imu = 0, frames = 0, black = 0, scans = 0;
  double mean_before = 0, mean_in_jump = 0;  // 0.60 and 0.65 against 0.70 and 0.75
  while (auto e = reader->next()) {
    if (const auto* s = std::get_if<ImuSample>(&e->data)) {
      ++imu;
      const double t = ns_to_s(s->t_ns - t0);
      EXPECT_FALSE(t >= 0.5 && t < 0.6) << "IMU sample inside the gap at " << t;
    } else if (const auto* f = std::get_if<StereoFrame>(&e->data)) {
      EXPECT_EQ((f->t_ns - t0) % 50'000'000, 4'000'000);  // the camera clock is 4 ms late
      const double t = ns_to_s(f->t_ns - t0 - 4'000'000);
      const bool dark = cv::countNonZero(f->left) == 0 && cv::countNonZero(f->right) == 0;
      EXPECT_EQ(dark, t >= 0.2 && t < 0.35) << "frame at " << t;
      black += dark;
      ++frames;
      const double mean = cv::mean(f->left)[0];
      if (t > 0.59 && t < 0.69) mean_before += mean / 2;
      if (t > 0.69 && t < 0.79) mean_in_jump += mean / 2;
    } else if (const auto* l = std::get_if<LidarScan>(&e->data)) {
      const double t = ns_to_s(l->t_ns - t0 + 2'000'000);
      EXPECT_FALSE(t >= 0.3 && t < 0.5) << "sweep inside the dropout at " << t;
      ++scans;
    }
  }
  EXPECT_EQ(frames, 21u);
  EXPECT_EQ(black, 3u);    // 0.20, 0.25, 0.30
  // The jump's gain 2.5, less what saturates at 255 (the hallway's walls are bright: 146 -> 250 grey).
  EXPECT_GT(mean_in_jump, 1.5 * mean_before) << mean_before << " -> " << mean_in_jump;
  EXPECT_EQ(scans, 10u - 2u);
  EXPECT_EQ(imu, 201u - 20u);  // 0.500 .. 0.595
  EXPECT_EQ(reader->groundtruth().size(), 201u);
}

}  // namespace
}  // namespace vilslam::sim
