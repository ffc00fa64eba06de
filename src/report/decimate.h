#pragma once
// Bounding what a report holds: every k-th element of a long sequence.
#include <cstddef>
#include <vector>

namespace vilslam::report {

// Indices 0, k, 2k, ... with k = ceil(n / max_count) (all of them when n <= max_count), plus n - 1 so that a
// path keeps its end. At most max_count + 1 indices; max_count must be positive.
std::vector<std::size_t> decimated_indices(std::size_t n, std::size_t max_count);

}  // namespace vilslam::report
