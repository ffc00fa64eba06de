// Bad ROS bags (truncated, unindexed, wrong image encoding, missing topic) end `info`, `run` and `export-bag`
// with exit code 2 and an error naming the bag (and the topic), and nothing is written.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "rosbag_test_util.h"
#include "synthetic_dataset.h"
#include "test_util.h"

namespace vilslam {
namespace {

namespace fs = std::filesystem;

class RosbagBadInput : public test::RosbagFixture {
 protected:
  std::string python_bag(const std::string& name, const std::string& options) {
    return RosbagFixture::python_bag(name, options, false);
  }

  // info (with --json), run and export-bag on the bag: each exit 2, message naming the bag and every
  // string in `named`, and no output file or folder left behind.
  void expect_refused(const std::string& bag, const std::vector<std::string>& named, const std::string& extra = "") {
    const std::string calib = " --calib " + folder_ + "/rig.yaml " + extra;
    const fs::path json = dir_ / "info.json", out = dir_ / "run_out", exported = dir_ / "exported.bag";
    const test::CliResult results[] = {
        test::run_cli("info " + bag + calib + " --deep --json " + json.string()),
        test::run_cli("run --mode vio " + bag + calib + " --out " + out.string()),
        test::run_cli("export-bag " + bag + calib + " --out " + exported.string()),
    };
    for (const test::CliResult& r : results) {
      EXPECT_EQ(r.exit_code, 2) << r.output;
      EXPECT_NE(r.output.find("error: " + bag), std::string::npos) << r.output;
      for (const std::string& s : named) EXPECT_NE(r.output.find(s), std::string::npos) << "no '" << s << "' in " << r.output;
    }
    for (const fs::path& p : {json, out, exported, fs::path(exported.string() + ".partial"), dir_ / "exported.rig.yaml"}) {
      EXPECT_FALSE(fs::exists(p)) << p;
    }
  }

};

TEST_F(RosbagBadInput, TruncatedBags) {
  const std::string good = python_bag("good", "--lidar velodyne");
  const std::string bytes = test::read_file_bytes(good);
  // Cut inside the file header, inside the message data, and inside the index at the end.
  for (const double keep : {0.001, 0.5, 0.999}) {
    SCOPED_TRACE(keep);
    const std::string bag = (dir_ / "truncated.bag").string();
    std::ofstream(bag, std::ios::binary).write(bytes.data(), static_cast<std::streamsize>(bytes.size() * keep));
    expect_refused(bag, {"truncated"});
  }
}

TEST_F(RosbagBadInput, UnindexedBag) {
  // A recording that was never closed: the file header's index_pos is still 0 and the index is missing.
  std::string bytes = test::read_file_bytes(python_bag("good", "--lidar velodyne"));
  const std::string field = "index_pos=";
  const std::size_t at = bytes.find(field);
  ASSERT_NE(at, std::string::npos);
  std::uint64_t index_pos = 0;
  std::memcpy(&index_pos, bytes.data() + at + field.size(), sizeof index_pos);
  ASSERT_GT(index_pos, 0u);
  ASSERT_LT(index_pos, bytes.size());
  bytes.resize(index_pos);
  std::memset(&bytes[at + field.size()], 0, sizeof index_pos);
  const std::string bag = (dir_ / "unindexed.bag").string();
  std::ofstream(bag, std::ios::binary).write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  expect_refused(bag, {"not indexed"});
}

TEST_F(RosbagBadInput, WrongImageEncoding) {
  const std::string bag = python_bag("yuv", "--left yuv422");
  expect_refused(bag, {"/cam0/image_raw", "yuv422", "mono8", "mono16", "bayer_rggb8"});
}

TEST_F(RosbagBadInput, MissingTopic) {
  const std::string bag = python_bag("good", "--lidar velodyne");
  expect_refused(bag, {"/stereo/left", "cam0", "not in the bag"}, "--topic cam0=/stereo/left");
}

TEST_F(RosbagBadInput, NoCalibration) {
  const std::string bag = python_bag("good", "--lidar velodyne");
  const auto r = test::run_cli("info " + bag);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find((dir_ / "good.rig.yaml").string()), std::string::npos) << r.output;
}

}  // namespace
}  // namespace vilslam
