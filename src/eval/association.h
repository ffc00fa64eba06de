#pragma once
// Timestamp association of an estimate with a ground truth: each estimated pose takes the nearest
// ground-truth pose in time if it is within max_diff_ns; one-to-one (a ground-truth pose claimed by
// several estimates keeps the closest one, the earlier estimate on a tie).
#include <cstddef>
#include <vector>

#include "common/types.h"

namespace vilslam::eval {

constexpr TimeNs kDefaultMaxDiffNs = 10'000'000;  // 10 ms

struct Association {
  std::vector<std::size_t> est_ids;  // increasing
  std::vector<std::size_t> gt_ids;   // increasing, same length
  std::size_t size() const { return est_ids.size(); }
};

// Both trajectories sorted by strictly increasing time (as read_trajectory guarantees).
Association associate(const Trajectory& est, const Trajectory& gt, TimeNs max_diff_ns = kDefaultMaxDiffNs);

// The poses of `traj` at `ids`, in order.
Trajectory select(const Trajectory& traj, const std::vector<std::size_t>& ids);

}  // namespace vilslam::eval
