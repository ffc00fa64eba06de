// Progress: the line's percent, elapsed time and ETA; redraws throttled, the line cleared at the end. (Silence
// when stderr is not a terminal: the CLI tests' captured output, tests/pipeline/test_run_cli.cpp.)
#include <gtest/gtest.h>

#include <cstdio>
#include <string>

#include "common/progress.h"

namespace vilslam {
namespace {

std::string contents(std::FILE* f) {
  std::string text;
  std::rewind(f);
  for (int c = std::fgetc(f); c != EOF; c = std::fgetc(f)) text.push_back(static_cast<char>(c));
  return text;
}

TEST(Progress, LineHasPercentElapsedAndEta) {
  EXPECT_EQ(Progress::line("run", 0.25, 10.0), "run  25% 0:10 elapsed, ETA 0:30");
  EXPECT_EQ(Progress::line("simulate", 0.999, 125.0), "simulate  99% 2:05 elapsed, ETA 0:00");
  EXPECT_EQ(Progress::line("map", 0.0, 3.0), "map   0% 0:03 elapsed, ETA --");
  EXPECT_EQ(Progress::line("map", 1.5, 3.0), "map 100% 0:03 elapsed, ETA 0:00");  // clamped
}

TEST(Progress, RedrawsAtMostFourTimesASecondAndClearsAtTheEnd) {
  std::FILE* f = std::tmpfile();
  ASSERT_NE(f, nullptr);
  double now_s = 100.0;
  {
    Progress p("run", 200.0, f, [&] { return now_s; });
    for (int i = 0; i <= 200; ++i) {  // 2 s of updates, every 10 ms
      p.update(i);
      now_s += 0.01;
    }
  }
  const std::string text = contents(f);
  std::fclose(f);
  std::size_t draws = 0;
  for (std::size_t at = text.find("elapsed"); at != std::string::npos; at = text.find("elapsed", at + 1)) ++draws;
  EXPECT_GE(draws, 8u);
  EXPECT_LE(draws, 9u);
  EXPECT_NE(text.find("run   0% 0:00 elapsed, ETA --"), std::string::npos) << text;
  EXPECT_NE(text.find("run  50% 0:01 elapsed, ETA 0:01"), std::string::npos) << text;
  EXPECT_EQ(text.substr(text.size() - 4), "\r\033[K");  // the line cleared
}

}  // namespace
}  // namespace vilslam
