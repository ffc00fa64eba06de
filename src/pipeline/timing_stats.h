#pragma once
// Summary of per-frame module timings (median, 95th percentile, maximum) for timings.json.
#include <cstddef>
#include <vector>

namespace vilslam {

struct TimingSummary {
  std::size_t count = 0;
  double median_ms = 0;
  double p95_ms = 0;
  double max_ms = 0;
};

// Nearest-rank percentiles of the samples; all zero when there is none.
TimingSummary summarize_timings(std::vector<double> samples_ms);

}  // namespace vilslam
