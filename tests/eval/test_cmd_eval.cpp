// The `vilslam eval` and `vilslam eval-map` commands, run as a user would.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "io/cloud_io.h"
#include "io/trajectory_io.h"
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

// evo_ape tum fr2_desk_groundtruth.txt fr2_desk_ORB.txt -a (SE(3) Umeyama, default association 0.01 s)
// gives APE mean 0.0074917768702161495 m (printed by evo's Python API in a published walk-through; evo_ape
// prints 0.007492) on 2,174 matched poses. The ground truth repeats a stamp at line 10863: it is dropped
// with a warning, the command succeeds. (One association of 2,174 differs from evo's on an exact tie,
// so the full-precision mean differs by 4e-8: docs/evaluation.md.)
TEST(CmdEval, ReproducesEvoOnTumFr2Desk) {
  VILSLAM_REQUIRE_SHARED_DATA(dir, "trajectories");
  const auto json = test::temp_dir() / "fr2.json";
  const std::string gt = dir + "/fr2_desk_groundtruth.txt";
  const test::CliResult r = test::run_cli("eval --est " + dir + "/fr2_desk_ORB.txt --gt " + gt +
                                          " --align se3 --json " + json.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find(gt + ":10863: timestamp 1311868229576000000 repeats line 10862"), std::string::npos)
      << r.output;
  const std::string doc = test::read_file_bytes(json);
  EXPECT_EQ(json_number(doc, "matched_poses", "matched_poses"), 2174);
  EXPECT_EQ(std::lround(json_number(doc, "ape", "mean") * 1e6), 7492);  // evo_ape's printed 0.007492
  EXPECT_NEAR(json_number(doc, "ape", "mean"), 0.0074917768702161495, 5e-7);
}

// Only a time that goes back is an error: exit code 2 naming file and line, no JSON written.
TEST(CmdEval, DecreasingTimestampIsExitTwo) {
  const auto dir = test::temp_dir();
  std::ofstream(dir / "est.txt") << "0 0 0 0 0 0 0 1\n1 1 0 0 0 0 0 1\n2 2 0 0 0 0 0 1\n3 3 0 0 0 0 0 1\n";
  std::ofstream(dir / "repeat.txt") << "0 0 0 0 0 0 0 1\n1 1 0 0 0 0 0 1\n1 5 0 0 0 0 0 1\n2 2 0 0 0 0 0 1\n"
                                       "3 3 0 0 0 0 0 1\n";
  std::ofstream(dir / "back.txt") << "0 0 0 0 0 0 0 1\n1 1 0 0 0 0 0 1\n2 2 0 0 0 0 0 1\n1.5 3 0 0 0 0 0 1\n";
  const std::string args = "eval --format tum --align none --est " + (dir / "est.txt").string() + " --json " +
                           (dir / "out.json").string() + " --gt ";
  const test::CliResult repeat = test::run_cli(args + (dir / "repeat.txt").string());
  ASSERT_EQ(repeat.exit_code, 0) << repeat.output;
  EXPECT_NE(repeat.output.find("repeat.txt:3: timestamp 1000000000 repeats line 2"), std::string::npos);
  EXPECT_LT(json_number(test::read_file_bytes(dir / "out.json"), "ape", "max"), 1e-9);  // line 3's pose dropped
  std::filesystem::remove(dir / "out.json");
  const test::CliResult back = test::run_cli(args + (dir / "back.txt").string());
  EXPECT_EQ(back.exit_code, 2) << back.output;
  EXPECT_NE(back.output.find((dir / "back.txt").string() + ":4: timestamp 1500000000 is not after"),
            std::string::npos) << back.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "out.json"));
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

// A room corner (floor and two walls, 6 m) and a small box face: ICP is constrained in every direction.
PointCloud corner_cloud() {
  PointCloud cloud;
  for (int x = 0; x < 60; ++x) {
    for (int y = 0; y < 60; ++y) {
      cloud.points.emplace_back(0.1f * x, 0.1f * y, 0.0f);
      cloud.points.emplace_back(0.1f * x, 0.0f, 0.05f * y);
      cloud.points.emplace_back(0.0f, 0.1f * x, 0.05f * y);
      cloud.points.emplace_back(2.0f + 0.01f * x, 3.0f, 0.01f * y);
    }
  }
  return cloud;
}

TEST(CmdEvalMap, ReportsMreAndWritesColoredMap) {
  const auto dir = test::temp_dir();
  const PointCloud model = corner_cloud();
  PointCloud map;
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

// A map in another world (85 deg of yaw, 2 m away): --first-pose and --gt bring it onto the model, ICP
// from the identity does not; bad pose files exit 2 naming the file.
TEST(CmdEvalMap, FirstPoseAlignmentFromPoseFiles) {
  const auto dir = test::temp_dir();
  const PointCloud model = corner_cloud();
  PointCloud map;
  const SE3 T_We_Wg(so3::exp_quat(Vec3(0.0, 0.0, 85.0 * M_PI / 180.0)), Vec3(1.5, -2.0, 0.3));
  for (const auto& p : model.points) map.points.push_back((T_We_Wg * p.cast<double>()).cast<float>());
  Trajectory gt, est;
  for (int i = 0; i < 100; ++i)
    gt.push_back({s_to_ns(1.0 + 0.01 * i), SE3(so3::exp_quat(Vec3(0, 0, 0.02 * i)), Vec3(1.0 + 0.02 * i, 2.0, 1.2))});
  for (int i = 0; i < 9; ++i) est.push_back({s_to_ns(1.005 + 0.1 * i), T_We_Wg * pose_at(gt, s_to_ns(1.005 + 0.1 * i))});
  write_cloud((dir / "model.ply").string(), model);
  write_cloud((dir / "map.ply").string(), map);
  write_trajectory((dir / "gt.tum").string(), gt, TrajectoryFormat::kTum);
  write_trajectory((dir / "est.tum").string(), est, TrajectoryFormat::kTum);
  const std::string args = "eval-map --map " + (dir / "map.ply").string() + " --model " + (dir / "model.ply").string();

  const test::CliResult r = test::run_cli(args + " --first-pose " + (dir / "est.tum").string() + " --gt " +
                                          (dir / "gt.tum").string() + " --json " + (dir / "mre.json").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("initial alignment: first pose at 1.005000000 s"), std::string::npos) << r.output;
  const std::string doc = test::read_file_bytes(dir / "mre.json");
  EXPECT_LT(json_number(doc, "mean_m", "mean_m"), 1e-4);
  EXPECT_NE(doc.find("\"rule\": \"first_pose\""), std::string::npos) << doc;
  EXPECT_EQ(json_number(doc, "initial_alignment", "first_pose_t_ns"), 1005000000.0);

  const test::CliResult identity = test::run_cli(args + " --json " + (dir / "identity.json").string());
  if (identity.exit_code == 0) {
    EXPECT_GT(json_number(test::read_file_bytes(dir / "identity.json"), "mean_m", "mean_m"), 0.05) << identity.output;
  } else {
    EXPECT_EQ(identity.exit_code, 2) << identity.output;
  }

  Trajectory late_gt = gt;
  for (TimedPose& p : late_gt) p.t_ns += kNsPerSecond;
  write_trajectory((dir / "late_gt.tum").string(), late_gt, TrajectoryFormat::kTum);
  std::ofstream(dir / "corrupt.tum") << "1.0 0 0 0 0 0 0 1\n2.0 0 0 zero 0 0 0 1\n";
  const std::string est_arg = " --first-pose " + (dir / "est.tum").string();
  for (const auto& [extra, named] :
       {std::pair{est_arg + " --gt " + (dir / "late_gt.tum").string(), std::string("est.tum")},
        std::pair{est_arg + " --gt " + (dir / "corrupt.tum").string(), std::string("corrupt.tum")},
        std::pair{est_arg + " --gt " + (dir / "missing").string(), std::string("missing")},
        std::pair{" --first-pose " + (dir / "corrupt.tum").string() + " --gt " + (dir / "gt.tum").string(),
                  std::string("corrupt.tum")},
        std::pair{est_arg, std::string("--gt")}}) {
    const test::CliResult bad = test::run_cli(args + extra);
    EXPECT_EQ(bad.exit_code, 2) << extra << "\n" << bad.output;
    EXPECT_NE(bad.output.find(named), std::string::npos) << extra << "\n" << bad.output;
  }
  EXPECT_NE(test::run_cli(args + est_arg + " --gt " + (dir / "late_gt.tum").string()).output.find("outside"),
            std::string::npos);
}

}  // namespace
}  // namespace vilslam
