#pragma once
// Helpers shared by the tests: the shared real-data folder and running the CLI.
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <string>
#include <system_error>
#include <vector>

namespace vilslam::test {

// The shared real-data folder: the environment's VILSLAM_SHARED_DATA, else ../shared/data (CMake cache).
inline std::string shared_data_root() {
  const char* env = std::getenv("VILSLAM_SHARED_DATA");
  return env != nullptr && *env != '\0' ? std::string(env) : std::string(VILSLAM_SHARED_DATA);
}

// Absolute path of a file or folder in the shared data, or "" when the data is absent.
inline std::string shared_data(const std::string& relative) {
  const std::filesystem::path p = std::filesystem::path(shared_data_root()) / relative;
  return std::filesystem::exists(p) ? p.string() : std::string();
}

// True when the environment says CI=true: there, real-data tests must not skip.
inline bool under_ci() {
  const char* ci = std::getenv("CI");
  return ci != nullptr && std::string(ci) == "true";
}

// Prints the line scripts/test counts ("[real data] ran Suite.Name: PATH").
inline void log_real_data_use(const std::string& path) {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  std::printf("[real data] ran %s.%s: %s\n", info->test_suite_name(), info->name(), path.c_str());
}

// Binds var to the shared-data path. When it is absent the test fails under CI and skips elsewhere, with a
// message naming the missing path ("shared data absent: ..."; scripts/test counts both outcomes).
#define VILSLAM_REQUIRE_SHARED_DATA(var, relative)                                                            \
  const std::string var = ::vilslam::test::shared_data(relative);                                             \
  if (var.empty()) {                                                                                          \
    if (::vilslam::test::under_ci())                                                                          \
      FAIL() << "shared data absent under CI=true: " << ::vilslam::test::shared_data_root() << "/" << (relative); \
    GTEST_SKIP() << "shared data absent: " << ::vilslam::test::shared_data_root() << "/" << (relative);        \
  }                                                                                                           \
  ::vilslam::test::log_real_data_use(var)

// The whole file as bytes ("" when it cannot be read).
inline std::string read_file_bytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

// This process's folder under the temp dir (test binaries of several worktrees may run at the same time).
// Everything a test writes goes below it; it is removed when the process's tests all pass and kept, with
// a message naming it, when one fails.
inline std::filesystem::path process_temp_root() {
  return std::filesystem::temp_directory_path() / "vilslam_tests" / std::to_string(::getpid());
}

class TempRootCleanup : public ::testing::Environment {
 public:
  void TearDown() override {
    if (!::testing::UnitTest::GetInstance()->Passed()) {
      std::printf("test files kept in %s\n", process_temp_root().c_str());
      return;
    }
    std::error_code ignored;
    std::filesystem::remove_all(process_temp_root(), ignored);
  }
};

// Registered before main() runs in every test binary that includes this header; gtest owns it.
inline ::testing::Environment* const kTempRootCleanup = ::testing::AddGlobalTestEnvironment(new TempRootCleanup);

// A fresh empty folder under process_temp_root(), unique per test.
inline std::filesystem::path temp_dir() {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  std::filesystem::path dir = process_temp_root() / (std::string(info->test_suite_name()) + "." + info->name());
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

struct CliResult {
  int exit_code = -1;
  std::string output;  // stdout and stderr together
};

// Writes bytes to path (replacing it), creating its folder.
inline void write_file_bytes(const std::filesystem::path& path, const std::string& bytes) {
  if (path.has_parent_path()) std::filesystem::create_directories(path.parent_path());
  std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes;
}

// The upper median (element n/2 in sorted order) of a sample; NaN when it is empty.
inline double median(std::vector<double> v) {
  if (v.empty()) return std::numeric_limits<double>::quiet_NaN();
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  return v[v.size() / 2];
}

// Runs a shell command, its output captured.
inline CliResult run_command(const std::string& command) {
  static int counter = 0;
  const std::filesystem::path out = process_temp_root() / ("cmd_" + std::to_string(counter++) + ".txt");
  std::filesystem::create_directories(out.parent_path());
  const std::string cmd = command + " > " + out.string() + " 2>&1";
  const int status = std::system(cmd.c_str());
  CliResult r;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  std::FILE* f = std::fopen(out.string().c_str(), "r");
  if (f) {
    char buf[4096];
    size_t n;
    while ((n = std::fread(buf, 1, sizeof buf, f)) > 0) r.output.append(buf, n);
    std::fclose(f);
  }
  return r;
}

// Runs the built `vilslam` CLI with the given argument string.
inline CliResult run_cli(const std::string& args) { return run_command(std::string(VILSLAM_CLI) + " " + args); }

// Paths of the scalar leaves of a YAML map ("vio.smoother.window_size"), in file order.
inline std::vector<std::string> yaml_key_paths(const YAML::Node& node, const std::string& prefix = "") {
  std::vector<std::string> paths;
  for (const auto& entry : node) {
    const std::string path = prefix + entry.first.Scalar();
    if (entry.second.IsMap()) {
      for (const std::string& p : yaml_key_paths(entry.second, path + ".")) paths.push_back(p);
    } else {
      paths.push_back(path);
    }
  }
  return paths;
}

}  // namespace vilslam::test
