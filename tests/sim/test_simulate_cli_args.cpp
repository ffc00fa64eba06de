#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "test_util.h"

namespace vilslam {
namespace {

// An option value the simulator cannot use is bad input: exit code 2, the reason printed, no output.
TEST(SimulateCli, UnusableLengthExitsWithTwoAndWritesNothing) {
  const std::filesystem::path out = test::temp_dir() / "short";
  const test::CliResult r = test::run_cli("simulate highbay --length 5 --out " + out.string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("target length"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(out));
}

// A route shifted into a wall (hallways are 2.0-2.4 m wide), or varied or repeated with a recorded trajectory,
// is refused.
TEST(SimulateCli, RouteVariedIntoAWallOrOfATrajectoryExitsWithTwo) {
  const std::filesystem::path out = test::temp_dir() / "shifted";
  test::CliResult r = test::run_cli("simulate hallway --preview --route-offset 1.5 --out " + out.string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("--route-offset: the shifted route passes within 0.3 m"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(out));
  const std::filesystem::path tum = test::temp_dir() / "flight.tum";
  std::ofstream(tum) << "1 0 0 1 0 0 0 1\n2 0.1 0 1 0 0 0 1\n";
  r = test::run_cli("simulate room --trajectory " + tum.string() + " --route-start 0.5 --out " + out.string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("--route-start, --route-offset and --laps vary the world's route"), std::string::npos)
      << r.output;
  EXPECT_FALSE(std::filesystem::exists(out));
  r = test::run_cli("simulate room --trajectory " + tum.string() + " --laps 2 --out " + out.string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_FALSE(std::filesystem::exists(out));
  r = test::run_cli("simulate room --duration 20 --laps 2 --out " + out.string());
  EXPECT_EQ(r.exit_code, 2) << r.output;  // the laps would not fit the duration's route
  EXPECT_FALSE(std::filesystem::exists(out));
}

TEST(SimulateCli, UnknownScenarioExitsWithTwo) {
  const test::CliResult r = test::run_cli("simulate volcano --out " + (test::temp_dir() / "v").string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
}

}  // namespace
}  // namespace vilslam
