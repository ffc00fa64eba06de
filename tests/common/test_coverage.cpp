#include <gtest/gtest.h>

#include "common/coverage.h"

namespace vilslam {
namespace {

std::vector<TimeNs> stamps(double from_s, double to_s, double step_s) {
  std::vector<TimeNs> t;
  for (double s = from_s; s <= to_s + 1e-9; s += step_s) t.push_back(s_to_ns(s));
  return t;
}

TEST(Coverage, AStretchWithoutPosesIsNotCovered) {
  // 10 Hz poses over [0, 4] s and [7, 10] s of a 10 s span: the 3 s hole is uncovered.
  std::vector<TimeNs> t = stamps(0.0, 4.0, 0.1);
  for (TimeNs s : stamps(7.0, 10.0, 0.1)) t.push_back(s);
  std::vector<bool> tracking(t.size(), true);
  for (std::size_t i = 0; i < 10; ++i) tracking[i] = false;  // the first second was not tracking
  const Coverage c = coverage_of(t, tracking, 10.0);
  EXPECT_NEAR(c.published, 0.7, 1e-9);
  EXPECT_NEAR(c.tracking, 0.6, 1e-9);
}

TEST(Coverage, FewerThanTwoPosesCoverNothing) {
  EXPECT_EQ(coverage_of({s_to_ns(1.0)}, {true}, 10.0).published, 0.0);
  EXPECT_EQ(coverage_of(stamps(0, 1, 0.1), std::vector<bool>(11, true), 0.0).published, 0.0);
}

}  // namespace
}  // namespace vilslam
