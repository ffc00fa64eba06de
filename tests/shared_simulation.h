#pragma once
// Simulated datasets shared by the test processes of one build. ctest runs every test of most suites as a
// process of its own, and several suites simulate the same sequence: `vilslam simulate ARGS` then runs once
// per (arguments, config, CLI build) and every later process reads the folder it wrote.
#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <system_error>
#include <vector>

#include "test_util.h"

namespace vilslam::test {

// The faults of the room's outage runs (tests/pipeline/test_lidar_loss_reset.cpp, the ROS node's reset test):
// the whole rig out from 7 s to 11 s.
constexpr const char* kRoomRigOutageConfig =
    "faults:\n  camera_blackouts: [[7.0, 11.0]]\n  lidar_dropouts: [[7.0, 11.0]]\n  imu_gaps: [[7.0, 11.0]]\n";

// 64-bit FNV-1a of s as 16 hex digits: a file name for a key.
inline std::string fnv1a_hex(const std::string& s) {
  std::uint64_t h = 14695981039346656037ull;
  for (const unsigned char c : s) h = (h ^ c) * 1099511628211ull;
  char out[17];
  std::snprintf(out, sizeof out, "%016llx", static_cast<unsigned long long>(h));
  return out;
}

// Folder of the dataset `vilslam simulate ARGS [--config C]` writes, C a file holding config_yaml (no --config
// when it is empty); "" after a failure, which is reported. The folder is shared: read it, never write in it.
// One process simulates while the others wait on a lock; the folder appears by one rename, complete. Entries
// of an earlier build of the CLI (another modification time or size) are removed when a new one is made.
inline std::string shared_simulation(const std::string& args, const std::string& config_yaml = "") {
  namespace fs = std::filesystem;
  const fs::path cli(VILSLAM_CLI);
  std::error_code ec;
  const std::string build = fnv1a_hex(std::to_string(fs::last_write_time(cli, ec).time_since_epoch().count()) + "/" +
                                      std::to_string(fs::file_size(cli, ec)));
  const fs::path root = fs::temp_directory_path() / "vilslam_tests" / "shared" / fnv1a_hex(cli.string());
  fs::create_directories(root);
  const std::string key = build + "_" + fnv1a_hex(args + '\n' + config_yaml);
  const fs::path dir = root / key;
  const int lock = ::open((root / (key + ".lock")).c_str(), O_RDWR | O_CREAT, 0644);
  if (lock < 0 || ::flock(lock, LOCK_EX) != 0) {
    ADD_FAILURE() << "cannot lock " << root / (key + ".lock");
    if (lock >= 0) ::close(lock);
    return "";
  }
  std::string out = (dir / "data").string();
  if (!fs::exists(dir)) {
    std::vector<fs::path> stale;
    for (const fs::directory_entry& e : fs::directory_iterator(root)) {
      if (e.path().filename().string().rfind(build, 0) != 0) stale.push_back(e.path());
    }
    for (const fs::path& p : stale) fs::remove_all(p, ec);
    const fs::path tmp = root / (key + ".tmp");
    fs::remove_all(tmp);
    fs::create_directories(tmp);
    std::string config;
    if (!config_yaml.empty()) {
      std::ofstream(tmp / "config.yaml") << config_yaml;
      config = " --config " + (tmp / "config.yaml").string();
    }
    const CliResult sim = run_cli("simulate " + args + config + " --out " + (tmp / "data").string());
    if (sim.exit_code == 0) {
      fs::rename(tmp, dir);
    } else {
      ADD_FAILURE() << "simulate " << args << ":\n" << sim.output;
      out.clear();
    }
  }
  ::flock(lock, LOCK_UN);
  ::close(lock);
  return out;
}

}  // namespace vilslam::test
