// The fuzz entries (fuzz/entries.h) in the normal build: every seed of fuzz/corpus is read, and every kept
// input of a fixed finding (fuzz/regressions/TARGET/NAME, docs/fuzzing.md) ends as the fix made it end.
#include <gtest/gtest.h>

#include <filesystem>
#include <set>
#include <string>
#include <vector>

#include "entries.h"
#include "test_util.h"

namespace vilslam::fuzz {
namespace {

namespace fs = std::filesystem;

const fs::path kFuzzDir = fs::path(VILSLAM_SOURCE_DIR) / "fuzz";

struct Finding {
  const char* target;
  const char* name;      // file in fuzz/regressions/<target>/
  const char* rejected;  // a part of the error the fix gives; nullptr when the fix makes the reader read it
};

// One row per finding fixed, in the order of docs/fuzzing.md.
const std::vector<Finding> kFindings = {
    {"cloud_ply", "skipped_element_count_hang", "truncated payload"},
    {"cloud_ply", "ascii_vertex_count_alloc", "truncated payload: header declares 4000000000 points"},
    {"cloud_pcd", "ascii_points_count_alloc", "truncated payload: header declares 4000000000 points"},
    {"ros_messages", "point_cloud2_ring_overflow", "not an integer in 0..65535"},
    {"calibration_yaml", "kalibr_resolution_int_overflow", "resolution: expected two positive integers"},
    {"ros_messages", "point_cloud2_empty_rows_hang", "PointCloud2 of width 0 has 4291875016 rows"},
    {"rosbag", "record_header_length_oom", "its header of 1633890109 bytes runs past the end of its chunk"},
};

Outcome run(const std::string& target, const fs::path& input) {
  const Entry entry = find_entry(target.c_str());
  if (entry == nullptr) throw std::invalid_argument("no fuzz entry " + target);
  const std::string bytes = test::read_file_bytes(input);
  return entry(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
}

TEST(FuzzSeeds, EverySeedIsRead) {
  int seeds = 0;
  for (const auto& dir : fs::directory_iterator(kFuzzDir / "corpus")) {
    for (const auto& seed : fs::directory_iterator(dir.path())) {
      const Outcome outcome = run(dir.path().filename().string(), seed.path());
      EXPECT_TRUE(outcome.read) << seed.path() << ": " << outcome.error;
      ++seeds;
    }
  }
  EXPECT_GT(seeds, 0);
}

TEST(FuzzRegressions, EachFindingEndsAsFixed) {
  for (const Finding& f : kFindings) {
    const Outcome outcome = run(f.target, kFuzzDir / "regressions" / f.target / f.name);
    if (f.rejected == nullptr) {
      EXPECT_TRUE(outcome.read) << f.target << "/" << f.name << ": " << outcome.error;
    } else {
      EXPECT_FALSE(outcome.read) << f.target << "/" << f.name;
      EXPECT_NE(outcome.error.find(f.rejected), std::string::npos) << f.target << "/" << f.name << ": " << outcome.error;
    }
  }
}

TEST(FuzzRegressions, EveryKeptInputIsListed) {
  std::set<fs::path> listed;
  for (const Finding& f : kFindings) listed.insert(fs::path(f.target) / f.name);
  const fs::path root = kFuzzDir / "regressions";
  if (!fs::exists(root)) return;
  for (const auto& file : fs::recursive_directory_iterator(root)) {
    if (file.is_regular_file()) {
      EXPECT_TRUE(listed.count(fs::relative(file.path(), root))) << file.path();
    }
  }
}

}  // namespace
}  // namespace vilslam::fuzz
