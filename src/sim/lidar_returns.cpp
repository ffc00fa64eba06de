#include "sim/lidar_returns.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "sim/rng.h"

namespace vilslam::sim {

LidarReturnModel ideal_returns() {
  return LidarReturnModel{};
}

double detection_range_m(const LidarReturnModel& model, double reflectivity, double cos_incidence) {
  if (!(model.range_at_10pct_m > 0)) return std::numeric_limits<double>::infinity();
  const double rho_eff = std::max(0.0, reflectivity * cos_incidence);
  return model.range_at_10pct_m * std::pow(rho_eff / 0.1, model.reflectivity_exponent);
}

double range_sigma_m(const LidarReturnModel& model, double range_noise_sigma_m, double range_m, double cos_incidence) {
  const double c = std::clamp(cos_incidence, 0.0, 1.0);
  const double tan_incidence = c > 0 ? std::min(10.0, std::sqrt(1.0 - c * c) / c) : 10.0;
  const double footprint_m = 0.5 * range_m * model.beam_divergence_rad * tan_incidence;
  return std::hypot(range_noise_sigma_m, footprint_m);
}

double returned_range_m(const LidarReturnModel& model, double range_noise_sigma_m, double true_range_m,
                        double neighbour_range_m, double reflectivity, double cos_incidence, std::uint64_t noise_seed,
                        std::uint64_t index) {
  Rng rng = rng_for(noise_seed, index);
  // The first draw is the range noise, as for an ideal sensor (same stream, same value).
  double range = true_range_m + range_sigma_m(model, range_noise_sigma_m, true_range_m, cos_incidence) * rng.gaussian();
  if (model.range_at_10pct_m > 0) {
    const double detect_m = detection_range_m(model, reflectivity, cos_incidence) *
                            (1.0 + model.detection_range_jitter * rng.gaussian());
    if (true_range_m > detect_m) return -1.0;
  }
  if (neighbour_range_m > 0 && std::abs(neighbour_range_m - true_range_m) > model.mixed_pixel_min_jump_m &&
      rng.chance(model.mixed_pixel_probability)) {
    range += rng.uniform() * (neighbour_range_m - true_range_m);
  }
  return range;
}

}  // namespace vilslam::sim
