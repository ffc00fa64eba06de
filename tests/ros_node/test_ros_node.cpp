// The live ROS1 node (apps/ros_node): a ROS master is started, vilslam_ros_node subscribes to the streams of
// a simulated room lap, play_and_record.py publishes the lap's bag (`vilslam export-bag`) at half speed as
// drivers would and records what the node publishes. The node's trajectories must be the offline run's; with the
// whole rig out for seconds, the node resets itself when LiDAR mapping is lost and re-localizes.
#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>
#include <yaml-cpp/yaml.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <string>
#include <thread>

#include "io/trajectory_io.h"
#include "shared_simulation.h"
#include "test_util.h"
#include "thread_sanitized.h"

namespace vilslam {
namespace {

namespace fs = std::filesystem;

// A background process started by the shell; its pid from the pid file.
pid_t start_background(const std::string& command, const fs::path& log, const fs::path& pid_file) {
  const auto r = test::run_command("(" + command + " > " + log.string() + " 2>&1 & echo $! > " + pid_file.string() + ")");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  std::ifstream in(pid_file);
  pid_t pid = 0;
  in >> pid;
  return pid;
}

// Waits up to timeout_s for the process to end; true when it did.
bool wait_for_exit(pid_t pid, double timeout_s) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  while (std::chrono::steady_clock::now() < deadline) {
    if (::kill(pid, 0) != 0) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  return false;
}

std::map<std::string, long> read_counts(const fs::path& path) {
  std::map<std::string, long> counts;
  std::ifstream in(path);
  std::string name;
  long n = 0;
  while (in >> name >> n) counts[name] = n;
  return counts;
}

// The poses of `live` at stamps `reference` also has: how many, and the largest position difference.
std::pair<std::size_t, double> compare(const Trajectory& live, const Trajectory& reference) {
  std::map<TimeNs, Vec3> by_stamp;
  for (const TimedPose& p : reference) by_stamp[p.t_ns] = p.T_W_B.translation();
  std::size_t matched = 0;
  double max_diff_m = 0;
  for (const TimedPose& p : live) {
    const auto it = by_stamp.find(p.t_ns);
    if (it == by_stamp.end()) continue;
    ++matched;
    max_diff_m = std::max(max_diff_m, (p.T_W_B.translation() - it->second).norm());
  }
  return {matched, max_diff_m};
}

// What a live run of the node on a bag left: the player's result, whether the node ended after Ctrl-C, its log.
struct LiveRun {
  test::CliResult played;
  bool node_ended = false;
  std::string node_log;
};

// Starts a ROS master of the test's own and the node (--rig DIR/NAME.rig.yaml, --out DIR/live_out, node_args),
// plays the bag as drivers would (at half speed times slower), recording what the node publishes in DIR/recorded,
// and stops both.
LiveRun play_through_node(const fs::path& dir, const std::string& name, const std::string& node_args,
                          double slower = 1.0) {
  const int port = 20000 + static_cast<int>(::getpid() % 20000);
  ::setenv("ROS_MASTER_URI", ("http://127.0.0.1:" + std::to_string(port)).c_str(), 1);
  ::setenv("ROS_HOSTNAME", "127.0.0.1", 1);
  ::setenv("ROS_HOME", (dir / "ros_home").c_str(), 1);
  LiveRun r;
  const pid_t master = start_background("rosmaster --core -p " + std::to_string(port), dir / "master.log", dir / "master.pid");
  EXPECT_GT(master, 0);
  const pid_t node = start_background(std::string(VILSLAM_ROS_NODE) + " --rig " + (dir / (name + ".rig.yaml")).string() +
                                          " --out " + (dir / "live_out").string() + " " + node_args +
                                          " imu0:=/imu0 cam0:=/cam0/image_raw cam1:=/cam1/image_raw lidar0:=/lidar0/points",
                                      dir / "node.log", dir / "node.pid");
  EXPECT_GT(node, 0);
  // Half speed; sanitized builds run slower (AddressSanitizer's about 3-5 times, ThreadSanitizer's 5-15 times),
  // and the bag is played slower for them so that the node can follow it.
  const double play_speed = (test::kThreadSanitized ? 0.05 : (VILSLAM_SANITIZED ? 0.1 : 0.5)) / slower;
  // Debian's interpreter: rospy and the message packages live in its dist-packages only.
  r.played = test::run_command("/usr/bin/python3 " + std::string(VILSLAM_SOURCE_DIR) +
                               "/tests/ros_node/play_and_record.py " + (dir / (name + ".bag")).string() + " " +
                               (dir / "recorded").string() + " --speed " + std::to_string(play_speed) +
                               " --topics /imu0 /cam0/image_raw /cam1/image_raw /lidar0/points");
  ::kill(node, SIGINT);  // the node finishes the run and writes --out
  r.node_ended = wait_for_exit(node, 120);
  ::kill(master, SIGINT);
  wait_for_exit(master, 30);
  if (!r.node_ended) ::kill(node, SIGKILL);
  r.node_log = test::read_file_bytes(dir / "node.log");
  return r;
}

TEST(RosNode, LiveNodePublishesTheOfflineTrajectory) {
  const fs::path dir = test::process_temp_root() / "RosNode";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const fs::path bag = dir / "room.bag";
  // Realistic sensors (the default): the camera's 3 ms clock offset puts the frames between IMU samples, where a live frame
  // that arrives after the next sample must still give the offline state (Vio's samples_for_frame).
  const std::string data = test::shared_simulation("room --length 8 --seed 2");
  ASSERT_FALSE(data.empty());
  const auto exported = test::run_cli("export-bag " + data + " --out " + bag.string());
  ASSERT_EQ(exported.exit_code, 0) << exported.output;
  const auto offline = test::run_cli("run --mode vil " + data + " --out " + (dir / "offline").string());
  ASSERT_EQ(offline.exit_code, 0) << offline.output;

  const LiveRun live = play_through_node(dir, "room", "");
  const std::string& node_log = live.node_log;
  ASSERT_EQ(live.played.exit_code, 0) << live.played.output << "\nnode:\n" << node_log;
  ASSERT_TRUE(live.node_ended) << node_log;
  EXPECT_NE(node_log.find("wrote " + (dir / "live_out").string()), std::string::npos) << node_log;
  EXPECT_EQ(node_log.find("Sanitizer"), std::string::npos) << node_log;  // a sanitized node's reports
  if (test::kThreadSanitized) {
    // Under ThreadSanitizer the node is about 20 times too slow to follow the bag even at 0.05x (most pairs
    // and sweeps dropped): what this build checks is the node's threads, above, not its trajectory.
    std::printf("[ros node] ThreadSanitizer build: trajectory not compared\n%s", node_log.c_str());
    return;
  }

  const auto read = [](const fs::path& p) { return read_trajectory(p.string(), TrajectoryFormat::kTum); };
  const Trajectory offline_camera = read(dir / "offline/vio_camera.tum");
  const Trajectory offline_lidar = read(dir / "offline/lidar.tum");
  const Trajectory offline_global = read(dir / "offline/lidar_global.tum");
  ASSERT_GT(offline_camera.size(), 100u);
  ASSERT_GT(offline_lidar.size(), 50u);
  // Every optimized stereo-frame state was published, where the offline run put it. With no pair dropped the
  // smoother sees the offline input: the same frames with the same IMU samples between them. (A machine too
  // slow for half speed, e.g. under a sanitizer, drops pairs by the overload policy: then only close.)
  const auto [camera_matched, camera_diff_m] = compare(read(dir / "recorded/camera_state.tum"), offline_camera);
  const bool pairs_dropped = node_log.find("overload policy 0 frames") == std::string::npos;
  EXPECT_GE(camera_matched, offline_camera.size() * (pairs_dropped ? 80 : 100) / 100) << node_log;
  EXPECT_LT(camera_diff_m, pairs_dropped ? 0.05 : 1e-6) << node_log;  // 1e-6: TUM's last digit
  // Every sweep's LiDAR pose; a loop correction may reach the mapper a sweep earlier or later than offline.
  const auto [lidar_matched, lidar_diff_m] = compare(read(dir / "recorded/lidar_pose.tum"), offline_lidar);
  const bool sweeps_dropped = !std::regex_search(node_log, std::regex("overload policy [0-9]+ frames, 0 sweeps"));
  EXPECT_GE(lidar_matched, offline_lidar.size() * (sweeps_dropped ? 80 : 100) / 100) << node_log;
  EXPECT_LT(lidar_diff_m, 0.05) << node_log;
  // The corrected path's last version holds the sweeps' loop-corrected poses.
  const auto [path_matched, path_diff_m] = compare(read(dir / "recorded/path.tum"), offline_global);
  EXPECT_GE(path_matched, offline_global.size() * (sweeps_dropped ? 80 : 100) / 100) << node_log;
  EXPECT_LT(path_diff_m, 0.05) << node_log;
  const auto counts = read_counts(dir / "recorded/counts.txt");
  std::printf("[ros node] camera states %zu of %zu within %.2e m, LiDAR poses %zu of %zu within %.2e m, path %zu of %zu "
              "within %.2e m, odometry %ld\n%s",
              camera_matched, offline_camera.size(), camera_diff_m, lidar_matched, offline_lidar.size(), lidar_diff_m,
              path_matched, offline_global.size(), path_diff_m, counts.at("odometry"), node_log.c_str());
  // IMU-rate odometry with its TF, and each mapped sweep's features.
  EXPECT_GE(counts.at("odometry"), static_cast<long>(read(dir / "offline/vio_imu.tum").size() * 9 / 10));
  EXPECT_EQ(counts.at("tf"), counts.at("odometry"));
  EXPECT_GE(counts.at("sparse_map"), static_cast<long>(offline_lidar.size() / 2));
  EXPECT_GT(counts.at("sparse_map_points"), 100 * counts.at("sparse_map"));
  // The node's own outputs on shutdown, as `vilslam run` writes them (without the pairs the policy dropped).
  EXPECT_GE(read(dir / "live_out/vio_camera.tum").size(), offline_camera.size() * (pairs_dropped ? 80 : 95) / 100);
}

// Two laps of the room with the whole rig out for 4 s (as tests/pipeline/test_lidar_loss_reset.cpp): live, the node
// too resets the whole state when LiDAR mapping is lost, and the new System re-localizes in the map of the first.
TEST(RosNode, LiveNodeResetsWhenLidarMappingIsLost) {
  const fs::path dir = test::process_temp_root() / "RosNodeReset";
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::ofstream(dir / "run.yaml") << "loop_closure:\n  min_time_gap_s: 4.0\n";  // a lap lasts about 10 s
  const std::string data = test::shared_simulation("room --length 8 --seed 2 --laps 2", test::kRoomRigOutageConfig);
  ASSERT_FALSE(data.empty());
  const auto exported = test::run_cli("export-bag " + data + " --out " + (dir / "room.bag").string());
  ASSERT_EQ(exported.exit_code, 0) << exported.output;

  // At a quarter of real time: a loaded machine drops no sweep around the outage.
  const LiveRun live = play_through_node(dir, "room", "--config " + (dir / "run.yaml").string(), 2.0);
  ASSERT_EQ(live.played.exit_code, 0) << live.played.output << "\nnode:\n" << live.node_log;
  ASSERT_TRUE(live.node_ended) << live.node_log;
  EXPECT_NE(live.node_log.find("LiDAR mapping was lost"), std::string::npos) << live.node_log;
  if (test::kThreadSanitized) return;  // too slow to follow the bag: most pairs and sweeps dropped
  const YAML::Node segments = YAML::LoadFile((dir / "live_out/segments.json").string())["segments"];
  ASSERT_EQ(segments.size(), 2u) << live.node_log;
  EXPECT_TRUE(segments[1]["relocalized"].as<bool>()) << live.node_log;
  const fs::path json = dir / "ape.json";
  const auto e = test::run_cli("eval --est " + (dir / "live_out/lidar_final.tum").string() + " --gt " + data +
                               " --gt-frame lidar --align se3 --json " + json.string());
  ASSERT_EQ(e.exit_code, 0) << e.output;
  // Offline the same lap ends 0.024 m off with the reset and 3.7 m without the check (LidarLossReset).
  EXPECT_LT(YAML::LoadFile(json.string())["ape"]["rmse"].as<double>(), 0.10) << e.output << live.node_log;
}

}  // namespace
}  // namespace vilslam
