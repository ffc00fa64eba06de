// The `vilslam eval` and `vilslam eval-map` commands, run as a user would.
#include <gtest/gtest.h>

#include "io/cloud_io.h"
#include "cli_output.h"
#include "test_util.h"

namespace vilslam {
namespace {

using test::json_number;

TEST(CmdEval, ReproducesEvoOnKitti00) {
  VILSLAM_REQUIRE_SHARED_DATA(dir, "trajectories");
  const auto json = test::temp_dir() / "kitti.json";
  const test::CliResult r =
      test::run_cli("eval --est " + dir + "/KITTI_00_ORB.txt --gt " + dir + "/KITTI_00_gt.txt --format kitti --times " +
                    dir + "/KITTI_00_gt_times.txt --align se3 --delta 10 --delta-unit m --json " + json.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::string doc = test::read_file_bytes(json);
  constexpr double kTol = 5e-6;
  EXPECT_NEAR(json_number(doc, "ape", "rmse"), 1.30345, kTol);
  EXPECT_NEAR(json_number(doc, "ape", "mean"), 1.15700, kTol);
  EXPECT_NEAR(json_number(doc, "ape", "median"), 1.06562, kTol);
  EXPECT_NEAR(json_number(doc, "ape", "max"), 3.58795, kTol);
  EXPECT_NEAR(json_number(doc, "rpe", "rmse"), 0.22626, kTol);
  EXPECT_NEAR(json_number(doc, "rpe", "mean"), 0.16902, kTol);
  EXPECT_EQ(json_number(doc, "matched_poses", "matched_poses"), 4541);
  EXPECT_NE(r.output.find("1.30345"), std::string::npos) << r.output;
}

TEST(CmdEval, IndexTimesGiveTheSameResult) {
  VILSLAM_REQUIRE_SHARED_DATA(dir, "trajectories");
  const auto json = test::temp_dir() / "kitti.json";
  const test::CliResult r = test::run_cli("eval --est " + dir + "/KITTI_00_ORB.txt --gt " + dir +
                                          "/KITTI_00_gt.txt --delta 10 --delta-unit m --json " + json.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NEAR(json_number(test::read_file_bytes(json), "ape", "rmse"), 1.30345, 5e-6);
}

TEST(CmdEval, EurocGroundTruthAgainstItselfWithPosYaw) {
  VILSLAM_REQUIRE_SHARED_DATA(gt, "trajectories/V102_groundtruth.csv");
  const auto dir = test::temp_dir();
  const test::CliResult r = test::run_cli("eval --est " + gt + " --gt " + gt + " --align posyaw --json " +
                                          (dir / "v.json").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::string doc = test::read_file_bytes(dir / "v.json");
  EXPECT_LT(json_number(doc, "ape", "max"), 1e-9);
  EXPECT_LT(json_number(doc, "rpe", "max"), 1e-9);
  EXPECT_EQ(json_number(doc, "matched_poses", "matched_poses"), 16702);
  EXPECT_NE(doc.find("\"mode\": \"posyaw\""), std::string::npos) << doc;
}

TEST(CmdEval, BadInputExitsTwoNamingFileAndLine) {
  const auto dir = test::temp_dir();
  std::ofstream(dir / "ok.txt") << "0 0 0 0 0 0 0 1\n1 1 0 0 0 0 0 1\n2 2 0 0 0 0 0 1\n";
  std::ofstream(dir / "corrupt.txt") << "0 0 0 0 0 0 0 1\n1 1 0 0 0 0\n";
  std::ofstream(dir / "nan.txt") << "0 0 0 0 0 0 0 1\n1 1 0 0 0 0 0 1\n2 nan 0 0 0 0 0 1\n";
  const std::string ok = (dir / "ok.txt").string();
  const struct {
    std::string est;
    std::string expected;
  } cases[] = {
      {(dir / "missing.txt").string(), (dir / "missing.txt").string() + ": cannot open"},
      {(dir / "corrupt.txt").string(), (dir / "corrupt.txt").string() + ":2:"},
      {(dir / "nan.txt").string(), (dir / "nan.txt").string() + ":3:"},
  };
  for (const auto& c : cases) {
    const test::CliResult r = test::run_cli("eval --format tum --est " + c.est + " --gt " + ok + " --json " +
                                            (dir / "out.json").string());
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find(c.expected), std::string::npos) << r.output;
    EXPECT_FALSE(std::filesystem::exists(dir / "out.json"));
  }
}

TEST(CmdEvalMap, ReportsMreAndWritesColoredMap) {
  const auto dir = test::temp_dir();
  PointCloud model, map;
  for (int x = 0; x < 60; ++x) {
    for (int y = 0; y < 60; ++y) {
      model.points.emplace_back(0.1f * x, 0.1f * y, 0.0f);
      model.points.emplace_back(0.1f * x, 0.0f, 0.1f * y);
      model.points.emplace_back(0.0f, 0.1f * x, 0.1f * y);
    }
  }
  for (const auto& p : model.points) map.points.push_back(p + Eigen::Vector3f(0.05f, -0.03f, 0.02f));
  write_cloud((dir / "model.ply").string(), model);
  write_cloud((dir / "map.ply").string(), map);
  const std::string args = "eval-map --map " + (dir / "map.ply").string() + " --model " + (dir / "model.ply").string();
  const test::CliResult r =
      test::run_cli(args + " --json " + (dir / "mre.json").string() + " --colored " + (dir / "colored.ply").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::string doc = test::read_file_bytes(dir / "mre.json");
  EXPECT_LT(json_number(doc, "mean_m", "mean_m"), 1e-4);
  const PointCloud colored = read_cloud((dir / "colored.ply").string());
  ASSERT_EQ(colored.size(), map.size());
  ASSERT_EQ(colored.intensity.size(), map.size());
  EXPECT_LT(colored.intensity[100], 1e-4);
  const test::CliResult raw = test::run_cli(args + " --no-align --json " + (dir / "raw.json").string());
  ASSERT_EQ(raw.exit_code, 0) << raw.output;
  EXPECT_GT(json_number(test::read_file_bytes(dir / "raw.json"), "mean_m", "mean_m"), 0.01);
  const test::CliResult missing = test::run_cli("eval-map --map " + (dir / "none.ply").string() + " --model " +
                                                (dir / "model.ply").string());
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_NE(missing.output.find("none.ply"), std::string::npos) << missing.output;
}

}  // namespace
}  // namespace vilslam
