#include "report/histogram.h"

#include <algorithm>
#include <stdexcept>

namespace vilslam::report {

Histogram histogram_from_zero(const std::vector<double>& samples, std::size_t bins) {
  if (bins == 0) throw std::invalid_argument("histogram_from_zero: bins must be positive");
  Histogram h;
  if (samples.empty()) return h;
  const double max = std::max(0.0, *std::max_element(samples.begin(), samples.end()));
  if (max == 0.0) {
    h.counts = {samples.size()};
    return h;
  }
  h.bin_width = max / static_cast<double>(bins);
  h.counts.assign(bins, 0);
  for (double x : samples) {
    const double bin = std::max(0.0, x) / h.bin_width;
    ++h.counts[std::min(bins - 1, static_cast<std::size_t>(bin))];
  }
  return h;
}

}  // namespace vilslam::report
