#pragma once
// What a real LiDAR makes of a beam's hit (docs/simulator.md, "Sensor realism"): weak echoes from dark
// or oblique surfaces are missed, the footprint of an oblique beam spreads the range, and a beam that
// straddles a depth edge returns a range between the two surfaces (a mixed pixel).
#include <cstdint>

namespace vilslam::sim {

// Every effect is off by default (an ideal sensor); lidar_sensor() sets each model's figures.
struct LidarReturnModel {
  // Detection range for a Lambertian target of 10 % reflectivity; 0 disables missed returns. A target of
  // effective reflectivity rho_eff = reflectivity * cos(incidence) is detected out to
  // range_at_10pct_m * (rho_eff / 0.1)^reflectivity_exponent (the exponent fits the Mid-360 data sheet's
  // 40 m at 10 % and 70 m at 80 %: ln(70/40) / ln 8).
  double range_at_10pct_m = 0.0;
  double reflectivity_exponent = 0.27;
  double detection_range_jitter = 0.1;  // relative 1-sigma pulse-to-pulse spread of that range
  // Full beam divergence; on a surface at incidence theta the footprint spreads the range by
  // 0.5 * range * divergence * tan(theta) (1 sigma, tan capped at 10), added to the range noise.
  double beam_divergence_rad = 0.0;
  // A beam whose next firing hits a surface more than mixed_pixel_min_jump_m nearer or farther straddles a
  // depth edge; with this probability it returns a range uniformly between the two. 0 disables.
  double mixed_pixel_probability = 0.0;
  double mixed_pixel_min_jump_m = 0.3;
};

// An ideal sensor: every hit returned at its range plus the configured range noise alone.
LidarReturnModel ideal_returns();

// The maximum detection range for a surface of this reflectivity at this cosine of incidence, before
// the pulse-to-pulse spread (infinite when the model disables missed returns).
double detection_range_m(const LidarReturnModel& model, double reflectivity, double cos_incidence);

// 1-sigma range error of a return: the sensor's range noise and the spread of an oblique footprint.
double range_sigma_m(const LidarReturnModel& model, double range_noise_sigma_m, double range_m, double cos_incidence);

// The measured range of a beam: its hit at true_range_m, the next firing of the same beam at
// neighbour_range_m (<= 0: none), perturbed by the model; negative when the echo is missed. The draws
// are a pure function of (noise_seed, index).
double returned_range_m(const LidarReturnModel& model, double range_noise_sigma_m, double true_range_m,
                        double neighbour_range_m, double reflectivity, double cos_incidence, std::uint64_t noise_seed,
                        std::uint64_t index);

}  // namespace vilslam::sim
