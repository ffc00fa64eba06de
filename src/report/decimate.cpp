#include "report/decimate.h"

#include <stdexcept>

namespace vilslam::report {

std::vector<std::size_t> decimated_indices(std::size_t n, std::size_t max_count) {
  if (max_count == 0) throw std::invalid_argument("decimated_indices: max_count must be positive");
  const std::size_t k = (n + max_count - 1) / max_count;
  std::vector<std::size_t> ids;
  for (std::size_t i = 0; i < n; i += (k == 0 ? 1 : k)) ids.push_back(i);
  if (n > 0 && ids.back() != n - 1) ids.push_back(n - 1);
  return ids;
}

}  // namespace vilslam::report
