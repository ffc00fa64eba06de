#pragma once
// A square, wrapping texture tile with its box-filtered mip pyramid and trilinear lookup.
#include <functional>
#include <vector>

namespace vilslam::sim {

class MipTile {
 public:
  // Level 0 has size x size texels (size a power of two) covering period_m in each axis; texel (x, y)
  // takes value(u_m, v_m, texel_m) at its centre. Rows are filled in parallel.
  MipTile(int size, double period_m, const std::function<float(double, double, double)>& value);

  // Trilinear lookup at surface coordinates (metres, wrapping) for a footprint of footprint_m per
  // pixel: the level whose texel matches the footprint (level 0 when the footprint is smaller).
  float sample(double u_m, double v_m, double footprint_m) const;
  // Bilinear lookup in the level nearest to the footprint (for smooth content; half the cost).
  float sample_nearest_level(double u_m, double v_m, double footprint_m) const;
  // Bilinear lookup in one level (for tests and inspection).
  float sample_level(double u_m, double v_m, int level) const;
  int num_levels() const { return static_cast<int>(levels_.size()); }
  const std::vector<float>& level(int i) const { return levels_[i]; }

 private:
  int size_;
  double period_m_;
  double texel_m_;
  std::vector<std::vector<float>> levels_;
};

}  // namespace vilslam::sim
