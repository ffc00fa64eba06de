#include "sim/imu_errors.h"

#include <cmath>

#include "sim/rng.h"

namespace vilslam::sim {
namespace {

double log_uniform(Rng& rng, double lo, double hi) { return std::exp(rng.uniform(std::log(lo), std::log(hi))); }

// 1 + a scale error on the diagonal; off it, each axis's tilt toward the other two, its two components uniform in
// +-max / sqrt(2) so that the axis stays within max of its nominal direction.
Mat3 axis_errors(Rng& rng, double max_scale_error, double max_misalignment_rad) {
  const double tilt = max_misalignment_rad / std::sqrt(2.0);
  Mat3 m;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) m(i, j) = i == j ? 1.0 + rng.uniform(-max_scale_error, max_scale_error) : rng.uniform(-tilt, tilt);
  }
  return m;
}

}  // namespace

ImuErrorRanges no_imu_errors() {
  ImuErrorRanges r;
  r.min_noise_factor = r.max_noise_factor = 1.0;
  r.max_scale_error = 0;
  r.max_misalignment_deg = 0;
  r.max_g_sensitivity_rad_s_per_m_s2 = 0;
  return r;
}

ImuErrors draw_imu_errors(const ImuNoise& datasheet, const ImuErrorRanges& ranges, std::uint64_t seed) {
  Rng rng(seed);
  ImuErrors e;
  e.noise = datasheet;
  const double lo = ranges.min_noise_factor, hi = ranges.max_noise_factor;
  e.noise.gyro_noise_density *= log_uniform(rng, lo, hi);
  e.noise.gyro_random_walk *= log_uniform(rng, lo, hi);
  e.noise.accel_noise_density *= log_uniform(rng, lo, hi);
  e.noise.accel_random_walk *= log_uniform(rng, lo, hi);
  const double misalignment_rad = ranges.max_misalignment_deg * M_PI / 180.0;
  e.gyro_axes = axis_errors(rng, ranges.max_scale_error, misalignment_rad);
  e.accel_axes = axis_errors(rng, ranges.max_scale_error, misalignment_rad);
  const double g = ranges.max_g_sensitivity_rad_s_per_m_s2;
  for (int i = 0; i < 9; ++i) e.g_sensitivity.data()[i] = rng.uniform(-g, g);
  return e;
}

ImuSample apply_axis_errors(const ImuErrors& errors, const ImuSample& ideal) {
  ImuSample s = ideal;
  s.gyro_rad_s = errors.gyro_axes * ideal.gyro_rad_s + errors.g_sensitivity * ideal.accel_m_s2;
  s.accel_m_s2 = errors.accel_axes * ideal.accel_m_s2;
  return s;
}

}  // namespace vilslam::sim
