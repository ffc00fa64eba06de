#pragma once
// Equal-width histograms of timing samples for the report's panels.
#include <cstddef>
#include <vector>

namespace vilslam::report {

struct Histogram {
  double lower = 0, bin_width = 0;  // bin i covers [lower + i w, lower + (i+1) w); the last bin includes its upper edge
  std::vector<std::size_t> counts;
};

// `bins` bins from 0 to the largest sample (samples are durations, >= 0); every sample falls into one.
// No samples: empty counts. All samples 0: one bin of width 0 holding them all. bins must be positive.
Histogram histogram_from_zero(const std::vector<double>& samples, std::size_t bins);

}  // namespace vilslam::report
