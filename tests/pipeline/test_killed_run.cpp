// `vilslam run`, `simulate` and `map` killed (SIGKILL) at moments spread over their run time leave their
// output either as it was before (a previous complete result, or none) or complete: never half-written
// (outputs are written under a temporary name and renamed into place at the end).
#include <gtest/gtest.h>

#include <signal.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <string>
#include <thread>
#include <vector>

#include "io/trajectory_io.h"
#include "map/simulated_highbay.h"
#include "test_util.h"

namespace vilslam {
namespace {

namespace fs = std::filesystem;

// Starts the CLI with args and kills it after delay_s unless it has finished by then; true when it was killed.
bool run_and_kill(const std::string& args, double delay_s) {
  const std::string command = std::string("exec ") + VILSLAM_CLI + " " + args + " > /dev/null 2>&1";
  const pid_t pid = fork();
  if (pid == 0) {
    execl("/bin/sh", "sh", "-c", command.c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  std::this_thread::sleep_for(std::chrono::duration<double>(delay_s));
  int status = 0;
  if (waitpid(pid, &status, WNOHANG) == pid) return false;  // finished before the kill
  kill(pid, SIGKILL);
  waitpid(pid, &status, 0);
  return true;
}

// A complete output: the reference's files (a folder's, recursively, or one file), identical but for a run's
// timings (a complete JSON and a complete csv).
void expect_complete(const fs::path& out, const fs::path& reference, const std::string& when) {
  if (fs::is_regular_file(reference)) {
    EXPECT_EQ(test::read_file_bytes(out), test::read_file_bytes(reference)) << when;
    return;
  }
  std::size_t files = 0;
  for (const auto& entry : fs::recursive_directory_iterator(reference)) {
    if (!entry.is_regular_file()) continue;
    ++files;
    const fs::path relative = fs::relative(entry.path(), reference);
    const std::string text = test::read_file_bytes(out / relative);
    if (relative == "timings.json") {
      EXPECT_TRUE(text.size() > 2 && text.substr(text.size() - 2) == "}\n") << when << ": " << relative;
    } else if (relative == "timing_samples.csv") {
      EXPECT_TRUE(text.rfind("series,ms\n", 0) == 0 && text.back() == '\n') << when << ": " << relative;
    } else {
      EXPECT_EQ(text, test::read_file_bytes(entry.path())) << when << ": " << relative;
    }
  }
  EXPECT_GT(files, 0u);
}

// Runs `args + reference` to completion, then kills `args + out` at `moments` instants spread over that run's
// time, over a previous complete result and into a new place; after each kill the output is absent or
// complete. extension: "" for a folder output, else the output file's extension. Returns the kills that landed
// before the command finished.
int kill_at_moments(const std::string& args, const fs::path& dir, const std::string& extension, int moments) {
  const fs::path reference = dir / ("reference" + extension);
  const auto start = std::chrono::steady_clock::now();
  EXPECT_EQ(test::run_cli(args + reference.string()).exit_code, 0) << args;
  const double run_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const fs::path previous = dir / ("previous" + extension);
  EXPECT_EQ(test::run_cli(args + previous.string()).exit_code, 0) << args;
  int killed = 0;
  for (int k = 1; k <= moments; ++k) {
    const double delay_s = run_s * (k < moments ? double(k) / moments : 0.97);
    const std::string when = args + ": killed after " + std::to_string(delay_s) + " s of a " +
                             std::to_string(run_s) + " s run";
    killed += run_and_kill(args + previous.string(), delay_s);
    if (fs::exists(previous)) expect_complete(previous, reference, when);
    const fs::path fresh = dir / ("fresh" + std::to_string(k) + extension);
    killed += run_and_kill(args + fresh.string(), delay_s);
    if (fs::exists(fresh)) expect_complete(fresh, reference, when);
  }
  std::printf("%s: %d of %d runs killed before they finished (complete run %.1f s)\n", args.c_str(), killed,
              2 * moments, run_s);
  return killed;
}

TEST(KilledRun, LeavesThePreviousResultOrNoneNeverAHalfWrittenOne) {
  const std::string& data = test::highbay_preview();
  ASSERT_FALSE(data.empty());
  EXPECT_GE(kill_at_moments("run --mode vil " + data + " --out ", test::temp_dir(), "", 6), 6);
}

// The dataset with its KITTI copy and TUM ground truth, published by one rename.
TEST(KilledSimulate, LeavesThePreviousDatasetOrNone) {
  EXPECT_GE(kill_at_moments("simulate highbay --preview --seed 3 --overwrite --out ", test::temp_dir(), "", 4), 4);
}

TEST(KilledMap, LeavesThePreviousCloudOrNone) {
  const std::string& data = test::highbay_preview();
  ASSERT_FALSE(data.empty());
  const fs::path dir = test::temp_dir();
  Trajectory T_W_L = test::groundtruth_lidar_poses(data);
  write_trajectory((dir / "poses.tum").string(), T_W_L, TrajectoryFormat::kTum);
  // 2 cm voxels: long enough a run for the kills to land in it.
  EXPECT_GE(kill_at_moments("map " + data + " --poses " + (dir / "poses.tum").string() + " --voxel 0.02 --out ", dir,
                            ".ply", 4),
            4);
}

}  // namespace
}  // namespace vilslam
