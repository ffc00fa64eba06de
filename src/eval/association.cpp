#include "eval/association.h"

#include <algorithm>
#include <cstdlib>

namespace vilslam::eval {

Association associate(const Trajectory& est, const Trajectory& gt, TimeNs max_diff_ns) {
  Association out;
  if (gt.empty()) return out;
  std::size_t best_est = 0;
  TimeNs best_diff = -1;
  std::size_t claimed_gt = gt.size();  // ground-truth index of the pending candidate
  const auto flush = [&]() {
    if (claimed_gt == gt.size()) return;
    out.est_ids.push_back(best_est);
    out.gt_ids.push_back(claimed_gt);
  };
  for (std::size_t i = 0; i < est.size(); ++i) {
    const TimeNs t = est[i].t_ns;
    const auto it = std::lower_bound(gt.begin(), gt.end(), t,
                                     [](const TimedPose& p, TimeNs value) { return p.t_ns < value; });
    std::size_t j = static_cast<std::size_t>(it - gt.begin());  // first gt pose at or after t
    if (j == gt.size() || (j > 0 && t - gt[j - 1].t_ns <= gt[j].t_ns - t)) --j;  // the one before is as near
    const TimeNs diff = std::llabs(gt[j].t_ns - t);
    if (diff > max_diff_ns) continue;
    // Nearest indices are non-decreasing in i, so all claims on one gt pose are consecutive.
    if (j == claimed_gt) {
      if (diff < best_diff) {
        best_est = i;
        best_diff = diff;
      }
      continue;
    }
    flush();
    claimed_gt = j;
    best_est = i;
    best_diff = diff;
  }
  flush();
  return out;
}

Trajectory select(const Trajectory& traj, const std::vector<std::size_t>& ids) {
  Trajectory out;
  out.reserve(ids.size());
  for (std::size_t id : ids) out.push_back(traj.at(id));
  return out;
}

}  // namespace vilslam::eval
