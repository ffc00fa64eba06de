#pragma once
// Summary statistics of an error sequence, defined as evo defines them (numpy): rmse = sqrt(mean(e^2)),
// std is the population standard deviation, median averages the two middle values of an even count.
#include <cstddef>
#include <vector>

namespace vilslam::eval {

struct ErrorStats {
  double rmse = 0, mean = 0, median = 0, std = 0, min = 0, max = 0;
  std::size_t count = 0;
};

// Throws std::invalid_argument on an empty sequence.
ErrorStats compute_stats(const std::vector<double>& values);

// Percentile q in [0, 100] with linear interpolation between order statistics (numpy's default).
double percentile(std::vector<double> values, double q);

}  // namespace vilslam::eval
