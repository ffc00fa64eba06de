#include "common/types.h"

#include <algorithm>

namespace vilslam {

TimeNs LidarScan::end_t_ns() const {
  float last_s = 0.0f;
  for (const LidarPoint& p : points) last_s = std::max(last_s, p.t_offset_s);
  return t_ns + s_to_ns(last_s);
}

}  // namespace vilslam
