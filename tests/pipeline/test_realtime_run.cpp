// The real-time mode (`vilslam run --realtime`) on the simulated 8 m room lap: at 1x (slower when sanitized) its live IMU-rate poses
// follow the smoother's; at 1000x the overload policy drops pairs and sweeps and the run still ends with its
// outputs. The offline run of the same lap is the reference.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "io/trajectory_io.h"
#include "shared_simulation.h"
#include "test_util.h"
#include "thread_sanitized.h"

namespace vilslam {
namespace {

namespace fs = std::filesystem;

class RealtimeRun : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    const fs::path dir = test::process_temp_root() / "room8_realtime";
    fs::remove_all(dir);
    fs::create_directories(dir);
    const std::string data = test::shared_simulation("room --length 8 --seed 2");
    ASSERT_FALSE(data.empty());
    // Real time is 1x for a machine that keeps up: a sanitized build runs 3-15 times slower (under AddressSanitizer
    // at 1x, 179 of 210 pairs were dropped and the VIO, given one frame in seven, lost track), so its clock is slowed.
    const std::string live_speed = test::kThreadSanitized ? "0.1" : (VILSLAM_SANITIZED ? "0.2" : "1");
    for (const auto& [run, speed] :
         {std::pair<std::string, std::string>{"offline", ""}, {"realtime", live_speed}, {"overload", "1000"}}) {
      const std::string pacing = speed.empty() ? "" : " --realtime " + speed;
      const test::CliResult r = test::run_cli("run --mode vil " + data + pacing + " --out " + (dir / run).string());
      ASSERT_EQ(r.exit_code, 0) << r.output;
    }
    runs_ = new fs::path(dir);
  }
  static void TearDownTestSuite() { delete runs_; }
  static Trajectory read(const std::string& run, const std::string& file) {
    return read_trajectory((*runs_ / run / file).string(), TrajectoryFormat::kTum);
  }
  static fs::path* runs_;
};
fs::path* RealtimeRun::runs_ = nullptr;

// The live poses are propagated from the same states as the smoother's IMU-rate poses, only without waiting
// for the next optimization: at the same samples they agree to within that optimization's correction, larger
// where stereo pairs were dropped (on this machine with two other runs busy, 155 of 200 pairs were dropped at 2x
// and the differences were 0.8 cm median, 7.7 cm at the 90th percentile).
TEST_F(RealtimeRun, RealtimeLivePosesFollowTheSmoothersPoses) {
  const Trajectory live = read("realtime", "vio_imu_live.tum");
  const Trajectory smoother = read("realtime", "vio_imu.tum");
  ASSERT_GT(live.size(), smoother.size() / 2);
  std::vector<double> gaps_m;
  for (const TimedPose& p : live) {
    const auto at = std::lower_bound(smoother.begin(), smoother.end(), p.t_ns,
                                     [](const TimedPose& q, TimeNs t) { return q.t_ns < t; });
    if (at != smoother.end() && at->t_ns == p.t_ns) gaps_m.push_back((at->T_W_B.translation() - p.T_W_B.translation()).norm());
  }
  ASSERT_GT(gaps_m.size(), live.size() / 2);
  std::sort(gaps_m.begin(), gaps_m.end());
  EXPECT_LT(gaps_m[gaps_m.size() / 2], 0.02);
  EXPECT_LT(gaps_m[gaps_m.size() * 9 / 10], 0.15);
  const std::string timings = test::read_file_bytes(*runs_ / "realtime" / "timings.json");
  for (const char* key : {"\"realtime\"", "\"imu_pose_latency\"", "\"camera_state_latency\"", "\"lidar_pose_latency\""}) {
    EXPECT_NE(timings.find(key), std::string::npos) << key;
  }
  EXPECT_EQ(test::read_file_bytes(*runs_ / "offline" / "timings.json").find("\"realtime\""), std::string::npos);
}

// At 1000x every module falls behind: the policy drops stereo pairs and sweeps (never IMU samples), and the
// run still ends with a trajectory of what it kept.
TEST_F(RealtimeRun, OverloadDropsPairsAndSweepsButFinishes) {
  const auto count = [](const std::string& run, const std::string& key) {
    const std::string timings = test::read_file_bytes(*runs_ / run / "timings.json");
    const std::size_t at = timings.find("\"" + key + "\":");
    EXPECT_NE(at, std::string::npos) << run << ": " << key;
    return at == std::string::npos ? 0L : std::stol(timings.substr(at + key.size() + 3));
  };
  EXPECT_GT(count("overload", "dropped_stereo_pairs"), 0);
  EXPECT_GT(count("overload", "dropped_sweeps"), 0);
  EXPECT_EQ(count("overload", "imu_samples"), count("offline", "imu_samples"));
  EXPECT_LT(read("overload", "vio_camera.tum").size(), read("offline", "vio_camera.tum").size());
  EXPECT_FALSE(read("overload", "lidar.tum").empty());
}

}  // namespace
}  // namespace vilslam
