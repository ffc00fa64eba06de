#include "pipeline/timing_stats.h"

#include <algorithm>
#include <cmath>

namespace vilslam {
namespace {

// Nearest-rank percentile of sorted samples: the ceil(p n)-th smallest.
double percentile(const std::vector<double>& sorted, double p) {
  const auto rank = static_cast<std::size_t>(std::ceil(p * static_cast<double>(sorted.size())));
  return sorted[std::clamp<std::size_t>(rank, 1, sorted.size()) - 1];
}

}  // namespace

TimingSummary summarize_timings(std::vector<double> samples_ms) {
  TimingSummary s;
  if (samples_ms.empty()) return s;
  std::sort(samples_ms.begin(), samples_ms.end());
  s.count = samples_ms.size();
  s.median_ms = percentile(samples_ms, 0.5);
  s.p95_ms = percentile(samples_ms, 0.95);
  s.max_ms = samples_ms.back();
  return s;
}

}  // namespace vilslam
