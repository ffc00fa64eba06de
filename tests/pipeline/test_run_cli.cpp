// `vilslam run`: output files, bit-identical reruns, bad input, and the VIO on a simulated sequence.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "eval/trajectory_eval.h"
#include "io/dataset.h"
#include "io/trajectory_io.h"
#include "test_util.h"

namespace vilslam {
namespace {

namespace fs = std::filesystem;

std::string read_all(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// Runs vio twice into a/ and b/ and expects identical trajectories (timings differ by nature).
void expect_deterministic(const std::string& dataset, const fs::path& dir) {
  for (const char* name : {"a", "b"}) {
    const test::CliResult r = test::run_cli("run --mode vio " + dataset + " --out " + (dir / name).string());
    ASSERT_EQ(r.exit_code, 0) << r.output;
  }
  for (const char* file : {"vio_camera.tum", "vio_imu.tum"}) {
    const std::string a = read_all(dir / "a" / file);
    EXPECT_FALSE(a.empty()) << file;
    EXPECT_EQ(a, read_all(dir / "b" / file)) << file;
  }
  EXPECT_TRUE(fs::exists(dir / "a" / "timings.json"));
  EXPECT_FALSE(fs::exists(dir / "a.partial"));
}

TEST(RunCli, EurocSliceIsDeterministic) {
  VILSLAM_REQUIRE_SHARED_DATA(path, "euroc/V1_01_easy_micro");
  expect_deterministic(path, test::temp_dir());
}

TEST(RunCli, BadInputExitsTwo) {
  const fs::path dir = test::temp_dir();
  EXPECT_EQ(test::run_cli("run --mode vio " + (dir / "missing").string() + " --out " + (dir / "o").string()).exit_code, 2);
  EXPECT_FALSE(fs::exists(dir / "o"));
}

TEST(RunCli, SimulatedHighbayPreviewHasSmallAte) {
  const fs::path dir = test::temp_dir();
  const std::string data = (dir / "highbay").string();
  const test::CliResult sim = test::run_cli("simulate highbay --preview --seed 3 --out " + data);
  ASSERT_EQ(sim.exit_code, 0) << sim.output;
  expect_deterministic(data, dir);

  const auto reader = open_dataset(data);
  Trajectory gt;
  for (const GroundTruthState& g : reader->groundtruth()) gt.push_back({g.t_ns, g.T_W_I});
  const Trajectory est = read_trajectory((dir / "a" / "vio_camera.tum").string(), TrajectoryFormat::kTum);
  eval::TrajectoryEvalConfig config;
  config.align = eval::AlignMode::kPosYaw;
  const eval::TrajectoryEvalReport report = eval::evaluate_trajectory(est, gt, config);
  std::printf("highbay preview: %zu matched poses over %.2f m, ATE RMSE (posyaw) %.4f m\n", report.matched_poses,
              report.path_length_m, report.ape.trans.rmse);
  EXPECT_GT(report.matched_poses, est.size() / 2);
  EXPECT_LT(report.ape.trans.rmse, 0.10);
}

}  // namespace
}  // namespace vilslam
