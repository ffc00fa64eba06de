#pragma once
// Regular sampling of a rectangle [0, size_u] x [0, size_v]: the centres of about spacing_m cells.
#include <algorithm>
#include <cmath>

namespace vilslam::sim {

template <typename Fn>
void for_each_grid_point(double size_u, double size_v, double spacing_m, Fn&& fn) {
  const int nu = std::max(1, static_cast<int>(std::ceil(size_u / spacing_m)));
  const int nv = std::max(1, static_cast<int>(std::ceil(size_v / spacing_m)));
  for (int i = 0; i < nu; ++i) {
    for (int j = 0; j < nv; ++j) fn((i + 0.5) * size_u / nu, (j + 0.5) * size_v / nv);
  }
}

}  // namespace vilslam::sim
