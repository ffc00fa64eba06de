// `vilslam map`: byte-identical reruns, PCD copy, bad input exits 2 without output.
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <fstream>
#include <vector>

#include "io/cloud_io.h"
#include "io/trajectory_io.h"
#include "simulated_highbay.h"
#include "test_util.h"

namespace vilslam {
namespace {

namespace fs = std::filesystem;

TEST(MapCli, RerunsAreByteIdentical) {
  const std::string& data = test::highbay_preview();
  ASSERT_FALSE(data.empty());
  const fs::path dir = test::temp_dir();
  const std::string poses = (dir / "lidar.tum").string();
  write_trajectory(poses, test::groundtruth_lidar_poses(data), TrajectoryFormat::kTum);
  const test::CliResult a = test::run_cli("map " + data + " --poses " + poses + " --out " + (dir / "a.ply").string());
  ASSERT_EQ(a.exit_code, 0) << a.output;
  EXPECT_NE(a.output.find("voxels:"), std::string::npos) << a.output;
  const test::CliResult b =
      test::run_cli("map " + data + " --poses " + poses + " --out " + (dir / "b.ply").string() + " --pcd");
  ASSERT_EQ(b.exit_code, 0) << b.output;
  const std::string bytes = test::read_file_bytes(dir / "a.ply");
  EXPECT_GT(bytes.size(), 100000u);
  EXPECT_EQ(bytes, test::read_file_bytes(dir / "b.ply"));
  EXPECT_EQ(read_cloud((dir / "b.pcd").string()).points, read_cloud((dir / "b.ply").string()).points);

  const test::CliResult coarse = test::run_cli("map " + data + " --poses " + poses + " --out " +
                                               (dir / "c.ply").string() + " --voxel 0.1 --min-hits 3");
  ASSERT_EQ(coarse.exit_code, 0) << coarse.output;
  EXPECT_LT(read_cloud((dir / "c.ply").string()).size(), read_cloud((dir / "a.ply").string()).size());
}

// The sweep counts printed by `vilslam map`: used, skipped, outside the window.
std::vector<int> sweep_counts(const std::string& output) {
  std::vector<int> n(3, -1);
  const auto at = output.find("sweeps: ");
  if (at == std::string::npos) return n;
  std::sscanf(output.c_str() + at, "sweeps: %d used, %d skipped (not covered by the poses), %d outside", &n[0], &n[1], &n[2]);
  return n;
}

// --start-s / --end-s (seconds after the first pose) split the sweeps between two maps.
TEST(MapCli, TimeWindowSplitsTheSweeps) {
  const std::string& data = test::highbay_preview();
  ASSERT_FALSE(data.empty());
  const fs::path dir = test::temp_dir();
  const std::string poses = (dir / "lidar.tum").string();
  write_trajectory(poses, test::groundtruth_lidar_poses(data), TrajectoryFormat::kTum);
  const std::string base = "map " + data + " --poses " + poses + " --voxel 0.05 --out ";
  const test::CliResult all = test::run_cli(base + (dir / "all.ply").string());
  const test::CliResult early = test::run_cli(base + (dir / "early.ply").string() + " --end-s 0.75");
  const test::CliResult late = test::run_cli(base + (dir / "late.ply").string() + " --start-s 0.75");
  ASSERT_EQ(all.exit_code, 0) << all.output;
  ASSERT_EQ(early.exit_code, 0) << early.output;
  ASSERT_EQ(late.exit_code, 0) << late.output;
  const std::vector<int> a = sweep_counts(all.output), e = sweep_counts(early.output), l = sweep_counts(late.output);
  EXPECT_GT(e[0], 3) << early.output;
  EXPECT_GT(l[0], 3) << late.output;
  EXPECT_EQ(e[0] + l[0], a[0]) << all.output << early.output << late.output;
  EXPECT_EQ(e[2], l[0]);
  EXPECT_EQ(l[2], e[0]);
  EXPECT_NE(early.output.find("outside the window (sweep ends from -inf to before 0.750 s after the first pose)"),
            std::string::npos)
      << early.output;
}

TEST(MapCli, BadInputExitsTwoWithoutOutput) {
  const std::string& data = test::highbay_preview();
  ASSERT_FALSE(data.empty());
  const fs::path dir = test::temp_dir();
  const Trajectory T_W_L = test::groundtruth_lidar_poses(data);
  const std::string poses = (dir / "lidar.tum").string();
  write_trajectory(poses, T_W_L, TrajectoryFormat::kTum);
  Trajectory late = T_W_L;
  for (TimedPose& p : late) p.t_ns += 1000 * kNsPerSecond;
  const std::string late_poses = (dir / "late.tum").string();
  write_trajectory(late_poses, late, TrajectoryFormat::kTum);
  const std::string corrupt = (dir / "corrupt.tum").string();
  std::ofstream(corrupt) << "1.0 0 0 0 0 0 0 1\n2.0 0 0 zero 0 0 0 1\n";
  const std::string out = (dir / "map.ply").string();
  for (const std::string& args : {"map " + (dir / "missing").string() + " --poses " + poses + " --out " + out,
                                  "map " + data + " --poses " + (dir / "missing.tum").string() + " --out " + out,
                                  "map " + data + " --poses " + corrupt + " --out " + out,
                                  "map " + data + " --poses " + late_poses + " --out " + out,
                                  "map " + data + " --poses " + poses + " --out " + out + " --voxel 0",
                                  "map " + data + " --poses " + poses + " --out " + out + " --voxel nan",
                                  "map " + data + " --poses " + poses + " --out " + out + " --start-s 1 --end-s 1",
                                  "map " + data + " --poses " + poses + " --out " + out + " --start-s 100",
                                  "map " + data + " --poses " + poses + " --out " + out + " --end-s nan",
                                  "map " + data + " --poses " + poses + " --out " + out + " --mixed-gap-ratio 0",
                                  "map " + data + " --poses " + poses + " --out " + out + " --mixed-gap-ratio nan",
                                  "map " + data + " --poses " + poses + " --out " + (dir / "map.txt").string()}) {
    const test::CliResult r = test::run_cli(args);
    EXPECT_EQ(r.exit_code, 2) << args << "\n" << r.output;
    std::string text = r.output;
    std::transform(text.begin(), text.end(), text.begin(), [](unsigned char ch) { return std::tolower(ch); });
    EXPECT_NE(text.find("error"), std::string::npos) << r.output;
  }
  std::size_t files = 0;
  for (const auto& entry : fs::directory_iterator(dir)) files += entry.is_regular_file() ? 1 : 0;
  EXPECT_EQ(files, 3u);  // the three poses files, no map and no temporary
}

}  // namespace
}  // namespace vilslam
