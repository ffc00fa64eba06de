// LiDAR mapping that declares itself lost, and the reset the run decides on it (docs/pipeline.md, "Resets after a
// lost map"): two laps of the simulated 8 m room with the whole rig out for 4 s (images black, no sweeps, no IMU
// samples) while the robot flies on. Without the check the first sweeps after the outage enter the map where the
// VIO's prior put them, metres and tens of degrees off, and the rest of the run is mapped in that displaced copy.
// With it those sweeps are rejected, the mapper is lost, the whole state is reset at the next check and the new
// segment re-localizes in the map of the first: the loop-closed poses stay on the truth. Without resets the mapper
// re-anchors: a fresh local map from the next sweep's predicted pose, and LiDAR poses to the end of the data.
// The reset's instant depends on the data only: with and without threads, the same files.
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "common/time.h"
#include "io/trajectory_io.h"
#include "shared_simulation.h"
#include "test_util.h"

namespace vilslam {
namespace {

namespace fs = std::filesystem;

constexpr double kSequenceStartS = 1.0;  // the simulator's first stamp (start_time_ns)
constexpr double kOutageEndS = 11.0;
constexpr const char* kShortGap = "loop_closure:\n  min_time_gap_s: 4.0\n";  // a lap lasts about 10 s

class LidarLossReset : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    root_ = new fs::path(test::process_temp_root() / "lidar_loss_reset");
    fs::remove_all(*root_);
    fs::create_directories(*root_);
    data_ = new std::string(test::shared_simulation("room --length 8 --seed 2 --laps 2", test::kRoomRigOutageConfig));
    ASSERT_FALSE(data_->empty());
    const std::vector<std::pair<std::string, std::string>> runs = {
        {"reset", ""},
        {"serial", "pipeline:\n  threads: false\n"},
        {"no_reset", "pipeline:\n  reset_on_lidar_lost: false\n"},
        {"unchecked", "lidar_mapper:\n  loss:\n    enabled: false\n"}};
    outputs_ = new std::vector<test::CliResult>;
    for (const auto& [name, extra] : runs) {
      std::ofstream(*root_ / (name + ".yaml")) << kShortGap << extra;
      outputs_->push_back(test::run_cli("run --mode vil " + data() + " --config " + (*root_ / (name + ".yaml")).string() +
                                        " --out " + run(name)));
      ASSERT_EQ(outputs_->back().exit_code, 0) << outputs_->back().output;
    }
  }
  static void TearDownTestSuite() {
    delete root_;
    delete data_;
    delete outputs_;
  }
  static std::string data() { return *data_; }
  static std::string run(const std::string& name) { return (*root_ / name).string(); }
  static const std::string& output(std::size_t i) { return (*outputs_)[i].output; }
  // SE(3)-aligned APE RMSE (m) of a run's loop-closed LiDAR poses.
  static double ape_m(const std::string& name) {
    const fs::path json = *root_ / (name + "_ape.json");
    const test::CliResult e = test::run_cli("eval --est " + run(name) + "/lidar_final.tum --gt " + data() +
                                            " --gt-frame lidar --align se3 --json " + json.string());
    EXPECT_EQ(e.exit_code, 0) << e.output;
    return YAML::LoadFile(json.string())["ape"]["rmse"].as<double>();
  }
  // The rows of lidar_status.csv whose status starts with "rejected_": (seconds since the start, status).
  static std::vector<std::pair<double, std::string>> rejected(const std::string& name) {
    std::ifstream in(run(name) + "/lidar_status.csv");
    std::string line;
    std::getline(in, line);
    std::vector<std::pair<double, std::string>> rows;
    while (std::getline(in, line)) {
      std::stringstream cells(line);
      std::string t, status;
      std::getline(cells, t, ',');
      std::getline(cells, status, ',');
      if (status.rfind("rejected_", 0) == 0) rows.emplace_back(ns_to_s(std::stoll(t)) - kSequenceStartS, status);
    }
    return rows;
  }

  static fs::path* root_;
  static std::string* data_;  // the shared simulation (read only)
  static std::vector<test::CliResult>* outputs_;  // reset, serial, no_reset, unchecked
};
fs::path* LidarLossReset::root_ = nullptr;
std::string* LidarLossReset::data_ = nullptr;
std::vector<test::CliResult>* LidarLossReset::outputs_ = nullptr;

TEST_F(LidarLossReset, TheMapperDeclaresItselfLostAndTheNewSegmentJoinsTheMap) {
  ASSERT_NE(outputs_, nullptr);
  // The first sweeps after the outage, and none elsewhere, are rejected; the third in a row makes the mapper lost.
  const auto rows = rejected("reset");
  ASSERT_EQ(rows.size(), 3u) << output(0);
  for (const auto& [t_s, status] : rows) {
    EXPECT_GT(t_s, kOutageEndS) << status;
    EXPECT_LT(t_s, kOutageEndS + 0.5) << status;
  }
  EXPECT_NE(output(0).find("LiDAR mapping lost at"), std::string::npos) << output(0);
  EXPECT_NE(output(0).find("(LiDAR mapping was lost)"), std::string::npos) << output(0);
  const YAML::Node timings = YAML::LoadFile(run("reset") + "/timings.json");
  ASSERT_EQ(timings["lidar_lost_t_ns"].size(), 1u);
  const double lost_s = ns_to_s(timings["lidar_lost_t_ns"][0].as<TimeNs>()) - kSequenceStartS;
  EXPECT_DOUBLE_EQ(lost_s, rows.back().first);
  // The reset comes at the next check (every 0.5 s of data), and its segment joins the first's map.
  const YAML::Node segments = YAML::LoadFile(run("reset") + "/segments.json")["segments"];
  ASSERT_EQ(segments.size(), 2u);
  const double reset_s = ns_to_s(segments[1]["start_t_ns"].as<TimeNs>()) - kSequenceStartS;
  EXPECT_GT(reset_s, lost_s);
  EXPECT_LE(reset_s, lost_s + 0.5 + 1e-6);
  ASSERT_TRUE(segments[1]["relocalized"].as<bool>()) << output(0);
  EXPECT_LT(ns_to_s(segments[1]["relocalized_t_ns"].as<TimeNs>()) - kSequenceStartS, reset_s + 5.0);
  // Measured (2026-12-06, gcc): 0.024 m reset, 3.74 m unchecked (69 deg of rotation error).
  const double reset_m = ape_m("reset"), unchecked_m = ape_m("unchecked");
  std::printf("SE(3) APE of lidar_final: %.4f m with the reset, %.4f m without the check\n", reset_m, unchecked_m);
  EXPECT_LT(reset_m, 0.06);
  EXPECT_GT(unchecked_m, 1.0);
  EXPECT_TRUE(rejected("unchecked").empty());
}

TEST_F(LidarLossReset, WithoutResetsTheMapperReanchorsAndMapsOn) {
  ASSERT_NE(outputs_, nullptr);
  EXPECT_FALSE(fs::exists(run("no_reset") + "/segments.json"));
  const YAML::Node timings = YAML::LoadFile(run("no_reset") + "/timings.json");
  EXPECT_EQ(timings["lidar_lost_t_ns"].size(), 0u);
  // The three rejected sweeps after the outage, then a fresh local map at the next sweep's prediction.
  const auto rows = rejected("no_reset");
  ASSERT_EQ(rows.size(), 3u) << output(2);
  std::ifstream in(run("no_reset") + "/lidar_status.csv");
  std::string line;
  double reanchored_s = -1.0;
  while (std::getline(in, line)) {
    if (line.find(",reanchored,") != std::string::npos) reanchored_s = ns_to_s(std::stoll(line)) - kSequenceStartS;
  }
  EXPECT_GT(reanchored_s, rows.back().first);
  EXPECT_LT(reanchored_s, rows.back().first + 0.2);
  const Trajectory lidar = read_trajectory(run("no_reset") + "/lidar.tum", TrajectoryFormat::kTum);
  const Trajectory vio = read_trajectory(run("no_reset") + "/vio_camera.tum", TrajectoryFormat::kTum);
  ASSERT_FALSE(lidar.empty());
  EXPECT_GT(ns_to_s(lidar.back().t_ns), ns_to_s(vio.back().t_ns) - 0.2);  // mapped to the end, as the VIO
  EXPECT_NE(output(2).find("LiDAR mapping re-anchored at"), std::string::npos) << output(2);
  EXPECT_EQ(output(2).find("LiDAR mapping lost at"), std::string::npos) << output(2);
  EXPECT_EQ(output(2).find("reset of the whole state"), std::string::npos) << output(2);
  // Covered but for the 4 s outage of the whole rig (about 21 s of data).
  EXPECT_GT(timings["coverage"]["lidar"]["published"].as<double>(), 0.7);
}

TEST_F(LidarLossReset, TheResetsInstantDependsOnTheDataOnly) {
  ASSERT_NE(outputs_, nullptr);
  for (const char* file : {"lidar.tum", "lidar_final.tum", "lidar_global.tum", "lidar_status.csv", "segments.json",
                           "loops.csv", "vio_camera.tum"}) {
    EXPECT_EQ(test::read_file_bytes(run("reset") + "/" + file), test::read_file_bytes(run("serial") + "/" + file)) << file;
  }
}

}  // namespace
}  // namespace vilslam
