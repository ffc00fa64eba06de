#include "sim/mip_tile.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace vilslam::sim {

MipTile::MipTile(int size, double period_m, const std::function<float(double, double, double)>& value)
    : size_(size), period_m_(period_m), texel_m_(period_m / size) {
  if (size < 1 || (size & (size - 1)) != 0) throw std::invalid_argument("MipTile size must be a power of two");
  std::vector<float> base(static_cast<std::size_t>(size) * size);
  tbb::parallel_for(0, size, [&](int y) {
    for (int x = 0; x < size; ++x) base[static_cast<std::size_t>(y) * size + x] = value((x + 0.5) * texel_m_, (y + 0.5) * texel_m_, texel_m_);
  });
  levels_.push_back(std::move(base));
  for (int n = size / 2; n >= 1; n /= 2) {
    const std::vector<float>& fine = levels_.back();
    std::vector<float> coarse(static_cast<std::size_t>(n) * n);
    for (int y = 0; y < n; ++y) {
      for (int x = 0; x < n; ++x) {
        const std::size_t i = static_cast<std::size_t>(2 * y) * (2 * n) + 2 * x;
        coarse[static_cast<std::size_t>(y) * n + x] = 0.25f * (fine[i] + fine[i + 1] + fine[i + 2 * n] + fine[i + 2 * n + 1]);
      }
    }
    levels_.push_back(std::move(coarse));
  }
}

float MipTile::sample_level(double u_m, double v_m, int level) const {
  const int n = size_ >> level;
  const std::vector<float>& t = levels_[level];
  // Texel centres sit at (i + 0.5) texels: shift by half a texel for bilinear weights.
  const double x = u_m / (texel_m_ * (1 << level)) - 0.5, y = v_m / (texel_m_ * (1 << level)) - 0.5;
  const double fx = std::floor(x), fy = std::floor(y);
  const float ax = static_cast<float>(x - fx), ay = static_cast<float>(y - fy);
  const int mask = n - 1;
  const auto ix = static_cast<long long>(fx), iy = static_cast<long long>(fy);
  const int x0 = static_cast<int>(ix & mask), x1 = static_cast<int>((ix + 1) & mask);
  const int y0 = static_cast<int>(iy & mask), y1 = static_cast<int>((iy + 1) & mask);
  const float* r0 = &t[static_cast<std::size_t>(y0) * n];
  const float* r1 = &t[static_cast<std::size_t>(y1) * n];
  const float top = r0[x0] + ax * (r0[x1] - r0[x0]);
  const float bottom = r1[x0] + ax * (r1[x1] - r1[x0]);
  return top + ay * (bottom - top);
}

float MipTile::sample_nearest_level(double u_m, double v_m, double footprint_m) const {
  const double level = std::log2(std::max(footprint_m / texel_m_, 1.0));
  return sample_level(u_m, v_m, std::min(num_levels() - 1, static_cast<int>(std::lround(level))));
}

float MipTile::sample(double u_m, double v_m, double footprint_m) const {
  const double level = std::log2(std::max(footprint_m / texel_m_, 1.0));
  const int top = num_levels() - 1;
  if (level >= top) return sample_level(u_m, v_m, top);
  const int l0 = static_cast<int>(level);
  const float a = static_cast<float>(level - l0);
  const float c0 = sample_level(u_m, v_m, l0);
  return a > 0 ? c0 + a * (sample_level(u_m, v_m, l0 + 1) - c0) : c0;
}

}  // namespace vilslam::sim
