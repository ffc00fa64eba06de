#pragma once
// How a simulated IMU differs from its data sheet (docs/simulator.md, "Sensor realism"; issue 61): per seed, the
// true white noise and bias walks are the data sheet's scaled by factors drawn between 0.5x and 3x, and the
// sensitive axes have scale factor errors, misalignment and (the gyroscope) a sensitivity to acceleration. None
// of it reaches the calibration the estimator reads, which keeps the data sheet's values as a real rig's does.
#include <cstdint>

#include "common/calibration.h"
#include "common/types.h"

namespace vilslam::sim {

struct ImuErrorRanges {
  double min_noise_factor = 0.5;             // each noise density and random walk is the data sheet's times a
  double max_noise_factor = 3.0;             //   factor drawn log-uniformly in [min, max]
  double max_scale_error = 0.005;            // per-axis scale factor error, uniform in [-max, max]
  double max_misalignment_deg = 0.2;         // each sensitive axis tilted off its nominal direction by up to this
  double max_g_sensitivity_rad_s_per_m_s2 = 1e-4;  // gyro rate per m/s^2 of specific force, per matrix entry
};

// Factors 1 and no axis errors: the data sheet's IMU (`--ideal-sensors`).
ImuErrorRanges no_imu_errors();

// One IMU's errors. Measured rate = gyro_axes omega + g_sensitivity f + bias + noise; measured specific force =
// accel_axes f + bias + noise (omega, f: the true rate and specific force in the body frame).
struct ImuErrors {
  ImuNoise noise;                      // the true densities and random walks (rate_hz the data sheet's)
  Mat3 gyro_axes = Mat3::Identity();   // 1 + scale error on the diagonal, misalignment off it
  Mat3 accel_axes = Mat3::Identity();
  Mat3 g_sensitivity = Mat3::Zero();
};

// A pure function of the seed; datasheet: the nominal noise the factors scale.
ImuErrors draw_imu_errors(const ImuNoise& datasheet, const ImuErrorRanges& ranges, std::uint64_t seed);

// The sample an IMU with these errors measures for an ideal (exact) one, before bias and noise.
ImuSample apply_axis_errors(const ImuErrors& errors, const ImuSample& ideal);

}  // namespace vilslam::sim
