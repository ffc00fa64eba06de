#include "sim/faults.h"

#include <algorithm>

namespace vilslam::sim {

bool in_fault(const std::vector<FaultInterval>& intervals, TimeNs since_start_ns) {
  const double t_s = ns_to_s(since_start_ns);
  return std::any_of(intervals.begin(), intervals.end(),
                     [t_s](const FaultInterval& f) { return t_s >= f.begin_s && t_s < f.end_s; });
}

}  // namespace vilslam::sim
