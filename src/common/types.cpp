#include "common/types.h"

#include <algorithm>

namespace vilslam {

TimeNs LidarScan::end_t_ns() const {
  float last_s = 0.0f;
  for (const LidarPoint& p : points) last_s = std::max(last_s, p.t_offset_s);
  return t_ns + s_to_ns(last_s);
}

SE3 pose_at(const Trajectory& poses, TimeNs t_ns) {
  const auto after = std::lower_bound(poses.begin(), poses.end(), t_ns,
                                      [](const TimedPose& p, TimeNs t) { return p.t_ns < t; });
  if (after == poses.begin()) return poses.front().T_W_B;
  if (after == poses.end()) return poses.back().T_W_B;
  const TimedPose& before = *(after - 1);
  const double alpha = static_cast<double>(t_ns - before.t_ns) / static_cast<double>(after->t_ns - before.t_ns);
  return interpolate(before.T_W_B, after->T_W_B, alpha);
}

}  // namespace vilslam
