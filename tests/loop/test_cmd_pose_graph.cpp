// `vilslam pose-graph`: a round trip on the synthetic square loop, and bad input -> exit 2 without output.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "io/trajectory_io.h"
#include "loop/square_loop.h"
#include "test_util.h"

namespace vilslam {
namespace {

namespace fs = std::filesystem;

std::string loop_row(const test::SquareLoop& s, std::size_t u, std::size_t v) {
  const SE3 T = test::true_loop(s, u, v).T_from_to;
  char buf[512];
  std::snprintf(buf, sizeof buf, "%lld,%lld,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%g,%g\n",
                static_cast<long long>(s.truth[u].t_ns), static_cast<long long>(s.truth[v].t_ns), T.translation().x(),
                T.translation().y(), T.translation().z(), T.quat().x(), T.quat().y(), T.quat().z(), T.quat().w(),
                test::kLoopSigmaM, test::kLoopSigmaRad);
  return buf;
}

struct Files {
  fs::path poses, loops, out;
};

Files write_inputs(const test::SquareLoop& s, const std::string& extra_loop_rows = "") {
  const fs::path dir = test::temp_dir();
  Files f{dir / "lidar.tum", dir / "loops.csv", dir / "corrected.tum"};
  write_trajectory(f.poses.string(), s.drifted, TrajectoryFormat::kTum);
  std::ofstream(f.loops) << "# from_t_ns,to_t_ns,tx,ty,tz,qx,qy,qz,qw,sigma_m,sigma_rad\n"
                         << loop_row(s, 0, s.lap_poses) << loop_row(s, 10, s.lap_poses + 10) << extra_loop_rows;
  return f;
}

std::string args(const Files& f) {
  return "pose-graph --poses " + f.poses.string() + " --loops " + f.loops.string() + " --out " + f.out.string() +
         " --odometry-sigma-m 0.02 --odometry-sigma-rad 0.002";
}

TEST(CmdPoseGraph, RoundTripClosesTheLoop) {
  const test::SquareLoop s = test::make_square_loop();
  const Files f = write_inputs(s);
  const test::CliResult r = test::run_cli(args(f));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const Trajectory corrected = read_trajectory(f.out.string(), TrajectoryFormat::kTum);
  ASSERT_EQ(corrected.size(), s.truth.size());
  EXPECT_EQ(corrected.back().t_ns, s.truth.back().t_ns);
  EXPECT_LT(test::end_to_start_m(s, corrected), test::end_to_start_m(s, s.drifted) / 50.0);
  EXPECT_LT(test::position_rmse(corrected, s.truth), test::position_rmse(s.drifted, s.truth) / 5.0);
  EXPECT_NE(r.output.find("loops 2"), std::string::npos) << r.output;
}

TEST(CmdPoseGraph, BadInputExitsTwoWithoutOutput) {
  const test::SquareLoop s = test::make_square_loop();
  const std::string good = loop_row(s, 20, 30);
  struct BadCase {
    std::string row, expected;
  };
  const BadCase bad_cases[] = {
      {"123," + good.substr(good.find(',') + 1), "loops.csv:4: time 123 ns is not a pose time"},
      {good.substr(0, good.find(',', good.find(',') + 1)) + ",nan,0,0,0,0,0,1\n", "loops.csv:4"},
      {good.substr(0, good.find(',', good.find(',') + 1)) + ",0,0,0,0,0,0.5,1\n", "loops.csv:4: quaternion is not unit"},
      {good.substr(0, good.find(',', good.find(',') + 1)) + ",0,0,0,0,0,0,1,0.1\n", "loops.csv:4: expected 9, 11 or 27"},
  };
  for (const BadCase& c : bad_cases) {
    const Files f = write_inputs(s, c.row);
    const test::CliResult r = test::run_cli(args(f));
    EXPECT_EQ(r.exit_code, 2) << c.row << r.output;
    EXPECT_NE(r.output.find(c.expected), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(f.out)) << c.row;
  }
  const Files f = write_inputs(s);
  fs::remove(f.poses);
  const test::CliResult r = test::run_cli(args(f));
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("lidar.tum"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(f.out));
}

}  // namespace
}  // namespace vilslam
