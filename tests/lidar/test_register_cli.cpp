// `vilslam register` on the shared real scan pair (HDL-32E, ~69k points) in both encodings.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "common/lie.h"
#include "test_util.h"

namespace vilslam {
namespace {

const std::string kConfig = std::string(VILSLAM_SOURCE_DIR) + "/config/lidar_hdl32e.yaml";

Mat4 read_matrix(const std::string& path) {
  std::ifstream in(path);
  Mat4 T;
  for (int i = 0; i < 16; ++i) in >> T(i / 4, i % 4);
  EXPECT_TRUE(in) << path;
  return T;
}

// The 16 numbers after "T_target_source" in our JSON output.
Mat4 json_matrix(const std::string& json) {
  std::string rest = json.substr(json.find("T_target_source") + 16);
  for (char& c : rest) {
    if (c == '[' || c == ']' || c == ',' || c == ':') c = ' ';
  }
  std::istringstream in(rest);
  Mat4 T;
  for (int i = 0; i < 16; ++i) in >> T(i / 4, i % 4);
  return T;
}

void expect_close(const Mat4& estimate, const Mat4& reference, const std::string& what) {
  const SE3 delta = SE3(reference).inverse() * SE3(estimate);
  EXPECT_LT(delta.translation().norm(), 0.05) << what;
  EXPECT_LT(so3::log(delta.rotation()).norm() * 180.0 / M_PI, 0.5) << what;
}

TEST(RegisterCli, RealPairLandsOnBothReferencesFromIdentity) {
  VILSLAM_REQUIRE_SHARED_DATA(lidar, "lidar");
  const Mat4 ref_small = read_matrix(lidar + "/small_gicp/T_target_source.txt");
  const Mat4 ref_fast = read_matrix(lidar + "/fast_gicp/relative.txt");  // also T_target_source
  const auto dir = test::temp_dir();
  const std::string pairs[2][3] = {
      {"small_gicp/source.ply", "small_gicp/target.ply", "ply.json"},
      {"fast_gicp/251371071.pcd", "fast_gicp/251370668.pcd", "pcd.json"}};
  for (const auto& pair : pairs) {
    const std::string json = (dir / pair[2]).string();
    const test::CliResult r = test::run_cli("register --source " + lidar + "/" + pair[0] + " --target " + lidar +
                                            "/" + pair[1] + " --config " + kConfig + " --json " + json);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_NE(r.output.find("T_target_source"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("degeneracy"), std::string::npos) << r.output;
    const Mat4 T = json_matrix(test::read_file_bytes(json));
    expect_close(T, ref_small, pair[2] + " vs small_gicp");
    expect_close(T, ref_fast, pair[2] + " vs fast_gicp");
    // Far from identity, so landing near the references is the registration's doing.
    EXPECT_GT(T.col(3).head(3).norm(), 0.4);
  }
}

TEST(RegisterCli, TwoRunsAreBitIdentical) {
  VILSLAM_REQUIRE_SHARED_DATA(lidar, "lidar");
  const auto dir = test::temp_dir();
  std::string outputs[2];
  for (int run = 0; run < 2; ++run) {
    const std::string json = (dir / ("run" + std::to_string(run) + ".json")).string();
    const test::CliResult r = test::run_cli("register --source " + lidar + "/small_gicp/source.ply --target " +
                                            lidar + "/small_gicp/target.ply --config " + kConfig + " --json " + json);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    outputs[run] = test::read_file_bytes(json);
  }
  EXPECT_FALSE(outputs[0].empty());
  EXPECT_EQ(outputs[0], outputs[1]);
}

TEST(RegisterCli, InitialGuessFileIsUsedAndBadInputExitsWithTwo) {
  VILSLAM_REQUIRE_SHARED_DATA(lidar, "lidar");
  const auto dir = test::temp_dir();
  const std::string init = (dir / "init.txt").string();
  std::ofstream(init) << test::read_file_bytes(lidar + "/small_gicp/T_target_source.txt");
  const std::string json = (dir / "r.json").string();
  const std::string args = "register --source " + lidar + "/small_gicp/source.ply --target " + lidar +
                           "/small_gicp/target.ply --config " + kConfig;
  ASSERT_EQ(test::run_cli(args + " --init " + init + " --json " + json).exit_code, 0);
  expect_close(json_matrix(test::read_file_bytes(json)), read_matrix(init), "from the reference");

  std::ofstream(dir / "bad_init.txt") << "1 0 0\n";
  const test::CliResult bad_init = test::run_cli(args + " --init " + (dir / "bad_init.txt").string());
  EXPECT_EQ(bad_init.exit_code, 2);
  EXPECT_NE(bad_init.output.find("bad_init.txt"), std::string::npos) << bad_init.output;
  const test::CliResult missing = test::run_cli("register --source " + (dir / "nope.pcd").string() + " --target " +
                                                lidar + "/small_gicp/target.ply");
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_NE(missing.output.find("nope.pcd"), std::string::npos) << missing.output;
}

}  // namespace
}  // namespace vilslam
