// Map reuse (docs/loop.md, "Map reuse"): a map saved from a lap of the simulated 8 m room, then another lap of
// the same world with other sensor noise, started half-way round and 0.3 m to the side (so it starts on the far
// side, facing the other way). `run --load-map` re-localizes within seconds of motion, and its LiDAR poses, in
// the map's frame with no alignment of the run, are within centimetres of the truth; without the map the same
// poses are metres off in that frame; with --save-map the run extends the map. A map that is not one is refused
// before anything is written.
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "io/trajectory_io.h"
#include "test_util.h"

namespace vilslam {
namespace {

namespace fs = std::filesystem;

class MapReuse : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    root_ = new fs::path(test::process_temp_root() / "map_reuse");
    fs::remove_all(*root_);
    // The second recording is a later session on the same clock (as a robot's wall clock is), so it may extend
    // the map.
    fs::create_directories(*root_);
    std::ofstream(*root_ / "later.yaml") << "motion:\n  start_time_ns: 100000000000\n";
    for (const std::string& args : {std::string("--seed 1 --out ") + (*root_ / "first").string(),
                                    std::string("--world-seed 1 --seed 2 --route-start 0.5 --route-offset 0.3 --config ") +
                                        (*root_ / "later.yaml").string() + " --out " + (*root_ / "second").string()}) {
      const test::CliResult sim = test::run_cli("simulate room --length 8 " + args);
      ASSERT_EQ(sim.exit_code, 0) << sim.output;
    }
    const test::CliResult run = test::run_cli("run --mode vil " + (*root_ / "first").string() + " --out " +
                                              (*root_ / "first_run").string() + " --save-map " + map());
    ASSERT_EQ(run.exit_code, 0) << run.output;
  }
  static void TearDownTestSuite() { delete root_; }

  static std::string map() { return (*root_ / "map").string(); }
  static std::string second() { return (*root_ / "second").string(); }

  // APE (m) of a run's lidar_final.tum in the map's frame: the ground truth moved there by the map's own fit.
  static double ape_in_map_frame(const fs::path& run) {
    const fs::path json = run / "ape_in_map.json";
    const test::CliResult r = test::run_cli("eval --est " + (run / "lidar_final.tum").string() + " --gt " + second() +
                                            " --gt-frame lidar --align none --map " + map() + " --map-gt " +
                                            (*root_ / "first").string() + " --json " + json.string());
    EXPECT_EQ(r.exit_code, 0) << r.output;
    return YAML::LoadFile(json.string())["ape"]["rmse"].as<double>();
  }

  static fs::path* root_;
};
fs::path* MapReuse::root_ = nullptr;

TEST_F(MapReuse, AnotherRouteRelocalizesWithinSecondsAndIsInTheMapsFrame) {
  const fs::path dir = test::temp_dir();
  const test::CliResult r = test::run_cli("run --mode vil " + second() + " --out " + (dir / "run").string() +
                                          " --load-map " + map() + " --save-map " + (dir / "extended").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("re-localized in the map"), std::string::npos) << r.output;
  const YAML::Node reloc = YAML::LoadFile((dir / "run/relocalization.json").string());
  ASSERT_TRUE(reloc["relocalized"].as<bool>());
  // Motion starts when the ground truth first moves (the lap starts at rest).
  const Trajectory gt = read_trajectory(second() + "/mav0/state_groundtruth_estimate0/data.csv", TrajectoryFormat::kEuroc);
  TimeNs moving_ns = gt.back().t_ns;
  for (const TimedPose& p : gt) {
    if ((p.T_W_B.translation() - gt.front().T_W_B.translation()).norm() > 0.01) {
      moving_ns = p.t_ns;
      break;
    }
  }
  EXPECT_LT(ns_to_s(reloc["relocalized_t_ns"].as<TimeNs>() - moving_ns), 5.0);
  EXPECT_GE(reloc["map_loops_in_graph"].as<int>(), 2);
  EXPECT_LT(ape_in_map_frame(dir / "run"), 0.05);

  // The map extended by the run: the loaded map's key frames and poses unchanged, then the run's, in the map's
  // frame (its final poses) and on the one clock.
  const Trajectory map_poses = read_trajectory(map() + "/poses.tum", TrajectoryFormat::kTum);
  const Trajectory extended = read_trajectory((dir / "extended/poses.tum").string(), TrajectoryFormat::kTum);
  const Trajectory run_poses = read_trajectory((dir / "run/lidar_final.tum").string(), TrajectoryFormat::kTum);
  ASSERT_EQ(extended.size(), map_poses.size() + run_poses.size());
  for (std::size_t i = 0; i < extended.size(); ++i) {
    const TimedPose& expected = i < map_poses.size() ? map_poses[i] : run_poses[i - map_poses.size()];
    EXPECT_EQ(extended[i].t_ns, expected.t_ns);
    EXPECT_LT((extended[i].T_W_B.translation() - expected.T_W_B.translation()).norm(), 1e-6);
  }
  const YAML::Node map_yaml = YAML::LoadFile(map() + "/map.yaml");
  const YAML::Node extended_yaml = YAML::LoadFile((dir / "extended/map.yaml").string());
  EXPECT_GT(extended_yaml["key_frames"].as<int>(), map_yaml["key_frames"].as<int>());
  const test::CliResult info = test::run_cli("map-info " + (dir / "extended").string());
  EXPECT_EQ(info.exit_code, 0) << info.output;

  // The same run without the map: its own frame starts where it stands, far from the map's.
  const test::CliResult alone = test::run_cli("run --mode vil " + second() + " --out " + (dir / "alone").string());
  ASSERT_EQ(alone.exit_code, 0) << alone.output;
  EXPECT_GT(ape_in_map_frame(dir / "alone"), 1.0);
  EXPECT_FALSE(fs::exists(dir / "alone/relocalization.json"));
}

TEST_F(MapReuse, AMapThatIsNotOneIsRefusedBeforeAnythingIsWritten) {
  const fs::path dir = test::temp_dir();
  fs::copy(map(), dir / "cut");
  const fs::path key_frames = dir / "cut/key_frames.bin";
  fs::resize_file(key_frames, fs::file_size(key_frames) / 2);
  const auto refused = [&](const std::string& args, const std::string& named) {
    const test::CliResult r = test::run_cli("run " + args + " --out " + (dir / "out").string());
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find(named), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(dir / "out"));
  };
  refused("--mode vil " + second() + " --load-map " + (dir / "cut").string(), key_frames.string());
  refused("--mode vil " + second() + " --load-map " + (dir / "none").string(), (dir / "none").string());
  refused("--mode vio " + second() + " --load-map " + map(), "mode vil with loop closure");
  // Extending the map by a recording that does not start after it (its clock would run backwards).
  refused("--mode vil " + (*root_ / "first").string() + " --load-map " + map() + " --save-map " +
              (dir / "extended").string(),
          "only a later recording extends it");
  EXPECT_FALSE(fs::exists(dir / "extended"));
}

}  // namespace
}  // namespace vilslam
