#pragma once
// The white noise of a real IMU stream, estimated from the stream alone (no ground truth), so that the
// calibration written for the estimator of a flight (`simulate --trajectory --imu`) depends on the IMU
// stream and the config only.
#include <cstddef>
#include <vector>

#include "common/calibration.h"
#include "common/types.h"

namespace vilslam::sim {

struct AllanAtSampleInterval {
  double tau0_s = 0;               // the median interval between samples
  double gyro_rad_s = 0;           // Allan deviation at tau0, RMS over the three axes
  double accel_m_s2 = 0;
  std::size_t pairs = 0;           // consecutive pairs used (pairs across a gap are skipped)
};

// Overlapping Allan variance at the shortest cluster time tau0 (clusters of one sample):
//   sigma^2(tau0) = 1 / (2 (N - 1)) sum_k (x[k+1] - x[k])^2,
// over consecutive pairs at most 1.5 tau0 apart (dropped samples and gaps are skipped). Zero pairs when
// the stream has fewer than two samples.
AllanAtSampleInterval allan_deviation_at_sample_interval(const std::vector<ImuSample>& samples);

// The noise a filter should assume for the stream: white-noise densities N = sigma(tau0) sqrt(tau0)
// (white noise has sigma^2(tau) = N^2 / tau), never below the datasheet's; the random walks and the rate
// stay the datasheet's. A smooth signal s(t) adds about (s' tau0)^2 / 2 to sigma^2(tau0), which at 200 Hz
// is small against a MAV's propeller vibration; vibration near the Nyquist frequency (anti-correlated
// neighbours) reads up to sqrt(2) high. Both err on the safe side; no further inflation is applied.
// With fewer than 10 pairs the datasheet is returned unchanged.
ImuNoise noise_from_stream(const std::vector<ImuSample>& samples, const ImuNoise& datasheet);

}  // namespace vilslam::sim
