#include <gtest/gtest.h>

#include <filesystem>

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

TEST(SimulateCli, UnknownScenarioExitsWithTwo) {
  const test::CliResult r = test::run_cli("simulate volcano --out " + (test::temp_dir() / "v").string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
}

}  // namespace
}  // namespace vilslam
