#include <gtest/gtest.h>

#include "eval/association.h"

namespace vilslam::eval {
namespace {

Trajectory at_times(const std::vector<TimeNs>& times) {
  Trajectory traj;
  for (TimeNs t : times) traj.push_back({t, SE3()});
  return traj;
}

constexpr TimeNs kMs = 1'000'000;

TEST(Association, NearestWithinMaxDifference) {
  const Trajectory gt = at_times({0, 100 * kMs, 200 * kMs, 300 * kMs});
  const Trajectory est = at_times({-20 * kMs, 3 * kMs, 104 * kMs, 160 * kMs, 291 * kMs, 400 * kMs});
  const Association a = associate(est, gt);
  EXPECT_EQ(a.est_ids, (std::vector<std::size_t>{1, 2, 4}));
  EXPECT_EQ(a.gt_ids, (std::vector<std::size_t>{0, 1, 3}));
  const Association wide = associate(est, gt, 60 * kMs);
  EXPECT_EQ(wide.est_ids, (std::vector<std::size_t>{1, 2, 3, 4}));
  EXPECT_EQ(wide.gt_ids, (std::vector<std::size_t>{0, 1, 2, 3}));
}

TEST(Association, OneToOneKeepsTheClosestEstimate) {
  const Trajectory gt = at_times({0, 100 * kMs});
  const Trajectory est = at_times({-4 * kMs, -1 * kMs, 2 * kMs, 99 * kMs, 101 * kMs});
  const Association a = associate(est, gt);
  EXPECT_EQ(a.est_ids, (std::vector<std::size_t>{1, 3}));  // tie 99 vs 101 ms: the earlier estimate
  EXPECT_EQ(a.gt_ids, (std::vector<std::size_t>{0, 1}));
}

TEST(Association, IdenticalTimesMatchAll) {
  const Trajectory t = at_times({1, 2, 3, 4, 5});
  const Association a = associate(t, t, 0);
  EXPECT_EQ(a.size(), 5u);
  EXPECT_EQ(select(t, a.gt_ids).back().t_ns, 5);
  EXPECT_EQ(associate(t, Trajectory{}).size(), 0u);
}

}  // namespace
}  // namespace vilslam::eval
