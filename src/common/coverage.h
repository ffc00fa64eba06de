#pragma once
// How much of a time span a series of poses covers (issue 60): each pose covers the time to the next one when that
// is at most 1.5 x the series' median interval, so a pose missing or a module that lost track leaves its stretch
// uncovered. A run reports it per module (pipeline/coverage.h), `vilslam eval` for the reference it was matched to.
#include <vector>

#include "common/time.h"

namespace vilslam {

struct Coverage {
  double published = 0.0;  // fraction of the span covered by the poses
  double tracking = 0.0;   // of it, by poses flagged tracking
};

// t_ns ascending, tracking one flag per pose; span_s > 0 (0 coverage otherwise, and with fewer than 2 poses).
Coverage coverage_of(const std::vector<TimeNs>& t_ns, const std::vector<bool>& tracking, double span_s);

}  // namespace vilslam
