#include "sim/imu_stream_noise.h"

#include <algorithm>
#include <cmath>

namespace vilslam::sim {

AllanAtSampleInterval allan_deviation_at_sample_interval(const std::vector<ImuSample>& samples) {
  AllanAtSampleInterval out;
  if (samples.size() < 2) return out;
  std::vector<TimeNs> intervals;
  intervals.reserve(samples.size() - 1);
  for (std::size_t k = 0; k + 1 < samples.size(); ++k) intervals.push_back(samples[k + 1].t_ns - samples[k].t_ns);
  std::nth_element(intervals.begin(), intervals.begin() + intervals.size() / 2, intervals.end());
  const TimeNs tau0_ns = intervals[intervals.size() / 2];
  out.tau0_s = ns_to_s(tau0_ns);

  double gyro_sq = 0, accel_sq = 0;
  for (std::size_t k = 0; k + 1 < samples.size(); ++k) {
    const TimeNs dt_ns = samples[k + 1].t_ns - samples[k].t_ns;
    if (dt_ns <= 0 || 2 * dt_ns > 3 * tau0_ns) continue;
    gyro_sq += (samples[k + 1].gyro_rad_s - samples[k].gyro_rad_s).squaredNorm();
    accel_sq += (samples[k + 1].accel_m_s2 - samples[k].accel_m_s2).squaredNorm();
    ++out.pairs;
  }
  if (out.pairs == 0) return out;
  // Overlapping Allan variance with clusters of one sample (IEEE Std 952-1997 Annex C), mean of the 3 axes.
  const double denominator = 2.0 * 3.0 * static_cast<double>(out.pairs);
  out.gyro_rad_s = std::sqrt(gyro_sq / denominator);
  out.accel_m_s2 = std::sqrt(accel_sq / denominator);
  return out;
}

ImuNoise noise_from_stream(const std::vector<ImuSample>& samples, const ImuNoise& datasheet) {
  const AllanAtSampleInterval allan = allan_deviation_at_sample_interval(samples);
  ImuNoise noise = datasheet;
  if (allan.pairs < 10) return noise;
  // White noise: sigma^2(tau) = N^2 / tau (IEEE Std 952-1997 Annex C, angle random walk), which at tau0 is
  // Kalibr's discrete sigma_d = N / sqrt(dt) (ethz-asl/kalibr wiki, "IMU Noise Model").
  const double sqrt_tau0 = std::sqrt(allan.tau0_s);
  noise.gyro_noise_density = std::max(datasheet.gyro_noise_density, allan.gyro_rad_s * sqrt_tau0);
  noise.accel_noise_density = std::max(datasheet.accel_noise_density, allan.accel_m_s2 * sqrt_tau0);
  return noise;
}

}  // namespace vilslam::sim
