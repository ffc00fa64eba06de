#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "common/publish_dir.h"
#include "test_util.h"

namespace vilslam {
namespace {

namespace fs = std::filesystem;

TEST(PublishDirectory, MovesTheStagingFolderWhereThereWasNone) {
  const fs::path dir = test::temp_dir();
  test::write_file_bytes(dir / "staging" / "a.txt", "new");
  publish_directory((dir / "staging").string(), (dir / "out").string());
  EXPECT_FALSE(fs::exists(dir / "staging"));
  EXPECT_EQ(test::read_file_bytes(dir / "out" / "a.txt"), "new");
}

TEST(PublishDirectory, ReplacesThePreviousFolderWholeAndLeavesNothingBehind) {
  const fs::path dir = test::temp_dir();
  test::write_file_bytes(dir / "out" / "a.txt", "old");
  test::write_file_bytes(dir / "out" / "only_old" / "b.txt", "old");
  test::write_file_bytes(dir / "staging" / "a.txt", "new");
  publish_directory((dir / "staging").string(), (dir / "out").string());
  EXPECT_EQ(test::read_file_bytes(dir / "out" / "a.txt"), "new");
  EXPECT_FALSE(fs::exists(dir / "out" / "only_old"));
  EXPECT_FALSE(fs::exists(dir / "staging"));
  EXPECT_FALSE(fs::exists(dir / "out.previous"));
}

TEST(PublishDirectory, AMissingStagingFolderIsAnErrorNamingIt) {
  const fs::path dir = test::temp_dir();
  test::write_file_bytes(dir / "out" / "a.txt", "old");
  try {
    publish_directory((dir / "missing").string(), (dir / "out").string());
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("missing"), std::string::npos) << e.what();
  }
  EXPECT_EQ(test::read_file_bytes(dir / "out" / "a.txt"), "old");
}

}  // namespace
}  // namespace vilslam
