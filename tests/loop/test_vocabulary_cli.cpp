// `vilslam vocabulary`: trains a loadable vocabulary bit-identically on EuRoC images; bad input exits 2
// without leaving an output file.
#include <gtest/gtest.h>

#include "loop/vocabulary.h"
#include "loop_test_data.h"
#include "test_util.h"

namespace vilslam {
namespace {

TEST(VocabularyCli, TrainsOnEurocImagesBitIdentically) {
  VILSLAM_REQUIRE_SHARED_DATA(euroc, "euroc/V1_01_easy_micro");
  const auto dir = test::temp_dir();
  const std::string args = "vocabulary --images " + euroc + " --k 8 --levels 2 --every 20 --out ";
  const test::CliResult a = test::run_cli(args + (dir / "a.voc").string());
  ASSERT_EQ(a.exit_code, 0) << a.output;
  EXPECT_NE(a.output.find("from 5 images"), std::string::npos) << a.output;
  const test::CliResult b = test::run_cli(args + (dir / "b.voc").string());
  ASSERT_EQ(b.exit_code, 0) << b.output;
  EXPECT_EQ(test::read_file_bytes(dir / "a.voc"), test::read_file_bytes(dir / "b.voc"));
  const Vocabulary v = Vocabulary::load((dir / "a.voc").string());
  EXPECT_EQ(v.branching(), 8);
  EXPECT_EQ(v.levels(), 2);
  EXPECT_GT(v.num_words(), 32u);
  EXPECT_LE(v.num_words(), 64u);
}

TEST(VocabularyCli, BadInputExitsTwoWithoutOutput) {
  const auto dir = test::temp_dir();
  const std::string out = (dir / "out.voc").string();
  std::filesystem::create_directories(dir / "empty");
  for (const std::string& bad : {"--images " + (dir / "missing").string(), "--images " + (dir / "empty").string()}) {
    const test::CliResult r = test::run_cli("vocabulary " + bad + " --out " + out);
    EXPECT_EQ(r.exit_code, 2) << bad << "\n" << r.output;
    EXPECT_FALSE(std::filesystem::exists(out)) << bad;
  }
  const std::string images = "--images " + (dir / "empty").string();
  for (const std::string& bad : {std::string("--k 1"), std::string("--levels 0"), std::string("--every 0")}) {
    const test::CliResult r = test::run_cli("vocabulary " + images + " " + bad + " --out " + out);
    EXPECT_EQ(r.exit_code, 2) << bad << "\n" << r.output;
    EXPECT_FALSE(std::filesystem::exists(out)) << bad;
  }
  const test::CliResult r = test::run_cli("vocabulary " + images + " --out " + (dir / "no_such" / "out.voc").string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
}

}  // namespace
}  // namespace vilslam
