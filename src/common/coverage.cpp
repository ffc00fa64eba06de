#include "common/coverage.h"

#include <algorithm>
#include <cstddef>

namespace vilslam {

Coverage coverage_of(const std::vector<TimeNs>& t_ns, const std::vector<bool>& tracking, double span_s) {
  Coverage c;
  if (t_ns.size() < 2 || !(span_s > 0.0)) return c;
  std::vector<TimeNs> intervals;
  for (std::size_t i = 1; i < t_ns.size(); ++i) intervals.push_back(t_ns[i] - t_ns[i - 1]);
  std::vector<TimeNs> sorted = intervals;
  std::nth_element(sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(sorted.size() / 2), sorted.end());
  const double max_interval_s = 1.5 * ns_to_s(sorted[sorted.size() / 2]);
  double published_s = 0.0, tracking_s = 0.0;
  for (std::size_t i = 0; i < intervals.size(); ++i) {
    const double interval_s = ns_to_s(intervals[i]);
    if (interval_s > max_interval_s) continue;
    published_s += interval_s;
    if (tracking[i]) tracking_s += interval_s;
  }
  c.published = std::min(1.0, published_s / span_s);
  c.tracking = std::min(1.0, tracking_s / span_s);
  return c;
}

}  // namespace vilslam
