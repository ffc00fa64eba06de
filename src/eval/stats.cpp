#include "eval/stats.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace vilslam::eval {

double percentile(std::vector<double> values, double q) {
  if (values.empty()) throw std::invalid_argument("percentile of an empty sequence");
  std::sort(values.begin(), values.end());
  const double rank = q / 100.0 * static_cast<double>(values.size() - 1);
  const std::size_t lo = static_cast<std::size_t>(std::floor(rank));
  const std::size_t hi = std::min(lo + 1, values.size() - 1);
  return values[lo] + (rank - static_cast<double>(lo)) * (values[hi] - values[lo]);
}

ErrorStats compute_stats(const std::vector<double>& values) {
  if (values.empty()) throw std::invalid_argument("statistics of an empty error sequence");
  ErrorStats s;
  s.count = values.size();
  const double n = static_cast<double>(values.size());
  double sum = 0, sum_sq = 0;
  for (double v : values) {
    sum += v;
    sum_sq += v * v;
  }
  s.mean = sum / n;
  s.rmse = std::sqrt(sum_sq / n);
  double var = 0;
  for (double v : values) var += (v - s.mean) * (v - s.mean);
  s.std = std::sqrt(var / n);
  const auto [lo, hi] = std::minmax_element(values.begin(), values.end());
  s.min = *lo;
  s.max = *hi;
  s.median = percentile(values, 50.0);
  return s;
}

}  // namespace vilslam::eval
