// A `vilslam run` killed (SIGKILL) at moments spread over its run time leaves its output folder either as it
// was before (a previous complete result, or none) or complete: never half-written (outputs go to
// OUT.partial and are renamed into place at the end).
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

// The files of a complete run: those of the reference, identical but for the timings (complete JSON).
void expect_complete(const fs::path& out, const fs::path& reference, const std::string& when) {
  for (const auto& entry : fs::directory_iterator(reference)) {
    const std::string name = entry.path().filename().string();
    const std::string text = test::read_file_bytes(out / name);
    if (name == "timings.json") {
      EXPECT_TRUE(text.size() > 2 && text.substr(text.size() - 2) == "}\n") << when << ": " << name;
    } else {
      EXPECT_EQ(text, test::read_file_bytes(entry.path())) << when << ": " << name;
    }
  }
}

TEST(KilledRun, LeavesThePreviousResultOrNoneNeverAHalfWrittenOne) {
  const std::string& data = test::highbay_preview();
  ASSERT_FALSE(data.empty());
  const fs::path dir = test::temp_dir();
  const fs::path reference = dir / "reference";
  const std::string args = "run --mode vil " + data + " --out ";
  const auto start = std::chrono::steady_clock::now();
  ASSERT_EQ(test::run_cli(args + reference.string()).exit_code, 0);
  const double run_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  // Over a previous complete result, and into a folder that did not exist.
  ASSERT_EQ(test::run_cli(args + (dir / "previous").string()).exit_code, 0);
  int killed = 0;
  for (int k = 1; k <= 6; ++k) {
    const double delay_s = run_s * (k < 6 ? k / 6.0 : 0.97);
    const std::string when = "killed after " + std::to_string(delay_s) + " s of a " + std::to_string(run_s) + " s run";
    killed += run_and_kill(args + (dir / "previous").string(), delay_s);
    if (fs::exists(dir / "previous")) expect_complete(dir / "previous", reference, when);
    const fs::path fresh = dir / ("fresh" + std::to_string(k));
    killed += run_and_kill(args + fresh.string(), delay_s);
    if (fs::exists(fresh)) expect_complete(fresh, reference, when);
  }
  std::printf("%d of 12 runs killed before they finished (reference run %.1f s)\n", killed, run_s);
  EXPECT_GE(killed, 6);  // most delays fall inside the run
}

}  // namespace
}  // namespace vilslam
