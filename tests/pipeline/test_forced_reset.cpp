// Forced resets (docs/loop.md, "Forced resets"): two laps of the simulated 8 m room, the whole state reset twice
// while the robot drives. Each new segment re-localizes in the map of the segments before it within seconds,
// and its final poses are then in that map's frame within centimetres of the truth (eval-segments). A reset that
// cannot re-localize is refused before anything is written.
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "io/trajectory_io.h"
#include "test_util.h"

namespace vilslam {
namespace {

namespace fs = std::filesystem;

class ForcedReset : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    root_ = new fs::path(test::process_temp_root() / "forced_reset");
    fs::remove_all(*root_);
    fs::create_directories(*root_);
    const test::CliResult sim = test::run_cli("simulate room --length 8 --seed 2 --laps 2 --out " + data());
    ASSERT_EQ(sim.exit_code, 0) << sim.output;
    // A lap lasts about 10 s: loop candidates 4 s old, as in LoopClosureRun.
    std::ofstream(*root_ / "short_gap.yaml") << "loop_closure:\n  min_time_gap_s: 4.0\n";
    output_ = new test::CliResult(test::run_cli("run --mode vil " + data() + " --config " +
                                                (*root_ / "short_gap.yaml").string() + " --reset-at 6 --reset-at 11 --out " +
                                                run()));
    ASSERT_EQ(output_->exit_code, 0) << output_->output;
  }
  static void TearDownTestSuite() {
    delete root_;
    delete output_;
  }
  static std::string data() { return (*root_ / "data").string(); }
  static std::string run() { return (*root_ / "run").string(); }

  static fs::path* root_;
  static test::CliResult* output_;
};
fs::path* ForcedReset::root_ = nullptr;
test::CliResult* ForcedReset::output_ = nullptr;

TEST_F(ForcedReset, EachSegmentJoinsTheMapWithinSecondsNearTheTruth) {
  ASSERT_NE(output_, nullptr);
  const YAML::Node segments = YAML::LoadFile(run() + "/segments.json")["segments"];
  ASSERT_EQ(segments.size(), 3u);
  for (std::size_t i = 1; i < 3; ++i) {
    ASSERT_TRUE(segments[i]["relocalized"].as<bool>()) << output_->output;
    const double join_s = ns_to_s(segments[i]["relocalized_t_ns"].as<TimeNs>() - segments[i]["start_t_ns"].as<TimeNs>());
    EXPECT_GT(join_s, 0.0);
    EXPECT_LT(join_s, 5.0) << "segment " << i;
    EXPECT_GE(segments[i]["map_loops_in_graph"].as<int>(), 2);
    EXPECT_NE(output_->output.find("segment " + std::to_string(i) + " (reset at"), std::string::npos) << output_->output;
  }
  const fs::path json = *root_ / "joins.json";
  const test::CliResult e = test::run_cli("eval-segments --run " + run() + " --gt " + data() + " --json " + json.string());
  ASSERT_EQ(e.exit_code, 0) << e.output;
  const YAML::Node joins = YAML::LoadFile(json.string())["segments"];
  ASSERT_EQ(joins.size(), 2u);
  for (const YAML::Node& j : joins) {
    ASSERT_TRUE(j["joined"].as<bool>());
    // The room lap is flown like a drone (up to 1.4 rad/s): the junction spans 1.5-2 s of that motion. Measured
    // with resets at 7 and 14 s: 4.6 cm / 0.52 deg and 6.3 cm / 0.59 deg, window rmse 2.5 and 0.6 cm. A segment
    // left in its own frame is metres off; one joined by a false map loop tens of centimetres.
    EXPECT_LT(j["junction_translation_m"].as<double>(), 0.10) << e.output;
    EXPECT_LT(j["junction_rotation_deg"].as<double>(), 1.5) << e.output;
    EXPECT_GE(j["joined_poses"].as<int>(), 20);
    EXPECT_LT(j["rmse_translation_m"].as<double>(), 0.05) << e.output;
  }
  // Every segment's sweeps are in the outputs, one after the other.
  const Trajectory final_poses = read_trajectory(run() + "/lidar_final.tum", TrajectoryFormat::kTum);
  const Trajectory odometry = read_trajectory(run() + "/lidar.tum", TrajectoryFormat::kTum);
  ASSERT_EQ(final_poses.size(), odometry.size());
  std::size_t sweeps = 0;
  for (const YAML::Node& s : segments) sweeps += s["sweeps"].as<std::size_t>();
  EXPECT_EQ(final_poses.size(), sweeps);
  EXPECT_LT(final_poses.front().t_ns, segments[1]["start_t_ns"].as<TimeNs>());
  EXPECT_GT(final_poses.back().t_ns, segments[2]["start_t_ns"].as<TimeNs>());
}

// The first sweep the mapper registers on the map after a join jumps from its prediction to where the map says;
// in the final trajectory that jump moves the segment before it (loop_closure.join_registration), so the step
// into that sweep is the prediction, not the jump: lidar_final's step differs from lidar.tum's by the jump.
TEST_F(ForcedReset, TheJoinSweepsJumpMovesTheSegmentInsteadOfStayingInTheTrajectory) {
  ASSERT_NE(output_, nullptr);
  const Trajectory final_poses = read_trajectory(run() + "/lidar_final.tum", TrajectoryFormat::kTum);
  const Trajectory odometry = read_trajectory(run() + "/lidar.tum", TrajectoryFormat::kTum);
  std::vector<double> jump_m;  // correction_m of lidar_status.csv, row by row with the trajectories
  std::ifstream status(run() + "/lidar_status.csv");
  std::string line;
  std::getline(status, line);
  while (std::getline(status, line)) {
    std::stringstream cells(line);
    std::vector<std::string> row;
    for (std::string cell; std::getline(cells, cell, ',');) row.push_back(cell);
    jump_m.push_back(std::stod(row.at(5)));
  }
  ASSERT_EQ(jump_m.size(), odometry.size());
  const YAML::Node segments = YAML::LoadFile(run() + "/segments.json")["segments"];
  double largest_jump_m = 0;
  for (std::size_t i = 1; i < segments.size(); ++i) {
    const TimeNs joined_t_ns = segments[i]["relocalized_t_ns"].as<TimeNs>();
    std::size_t k = 0;
    while (k < odometry.size() && odometry[k].t_ns <= joined_t_ns) ++k;
    ASSERT_LT(k, odometry.size());
    const SE3 odometry_step = odometry[k - 1].T_W_B.inverse() * odometry[k].T_W_B;
    const SE3 final_step = final_poses[k - 1].T_W_B.inverse() * final_poses[k].T_W_B;
    const double difference_m = (odometry_step.translation() - final_step.translation()).norm();
    std::printf("segment %zu: join sweep's jump %.4f m, final step differs by %.4f m\n", i, jump_m[k], difference_m);
    EXPECT_NEAR(difference_m, jump_m[k], 0.3 * jump_m[k] + 0.005) << "segment " << i;
    largest_jump_m = std::max(largest_jump_m, jump_m[k]);
  }
  EXPECT_GT(largest_jump_m, 0.03);  // the check above tells the two apart
}

// With no loop verified by vision at all (descriptor matching made impossible), a segment still joins the map
// where the previous one ended: the map's last pose carried across the reset by the segment's first motion,
// verified by ICP of the key scans; without that resume guess it never joins.
TEST_F(ForcedReset, WithoutVisionTheResumeGuessVerifiedByIcpJoinsTheMap) {
  const fs::path dir = test::temp_dir();
  const std::string blind = "loop_closure:\n  min_time_gap_s: 4.0\n  min_descriptor_matches: 100000\n";
  std::ofstream(dir / "blind.yaml") << blind;
  std::ofstream(dir / "blind_no_resume.yaml") << blind << "  resume_window_s: 0\n";
  const auto join = [&](const std::string& config) {
    const test::CliResult r = test::run_cli("run --mode vil " + data() + " --config " + (dir / config).string() +
                                            " --reset-at 6 --out " + (dir / config).string() + ".run");
    EXPECT_EQ(r.exit_code, 0) << r.output;
    return YAML::LoadFile((dir / config).string() + ".run/segments.json")["segments"][1];
  };
  const YAML::Node resumed = join("blind.yaml");
  ASSERT_TRUE(resumed["relocalized"].as<bool>());
  const double join_s = ns_to_s(resumed["relocalized_t_ns"].as<TimeNs>() - resumed["start_t_ns"].as<TimeNs>());
  EXPECT_LT(join_s, 3.0);
  const fs::path json = dir / "joins.json";
  const test::CliResult e = test::run_cli("eval-segments --run " + (dir / "blind.yaml.run").string() + " --gt " +
                                          data() + " --json " + json.string());
  ASSERT_EQ(e.exit_code, 0) << e.output;
  const YAML::Node j = YAML::LoadFile(json.string())["segments"][0];
  std::printf("joined by the resume guess after %.2f s: junction %.3f m / %.2f deg\n", join_s,
              j["junction_translation_m"].as<double>(), j["junction_rotation_deg"].as<double>());
  // Measured: gcc 5.2 cm / 0.57 deg (2026-11-28); clang's ASan build of older code 15.7 cm / 0.91 deg (builds land
  // differently; the lap's turns at the reset make the guess's ICP sensitive). A segment left in its own frame is
  // metres off.
  EXPECT_LT(j["junction_translation_m"].as<double>(), 0.25) << e.output;
  EXPECT_LT(j["junction_rotation_deg"].as<double>(), 1.5) << e.output;
  EXPECT_FALSE(join("blind_no_resume.yaml")["relocalized"].as<bool>());
}

TEST_F(ForcedReset, AResetThatCannotRelocalizeIsRefusedBeforeAnythingIsWritten) {
  const fs::path dir = test::temp_dir();
  const auto refused = [&](const std::string& args, const std::string& named) {
    const test::CliResult r = test::run_cli("run " + args + " --out " + (dir / "out").string());
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find(named), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(dir / "out"));
  };
  refused("--mode vio " + data() + " --reset-at 5", "mode vil with loop closure");
  refused("--mode vil " + data() + " --reset-at 9 --reset-at 4", "increasing");
  refused("--mode vil " + data() + " --reset-at -1", "positive");
}

}  // namespace
}  // namespace vilslam
