#pragma once
// IMU measurements derived exactly from a trajectory, plus axis errors, white noise and bias random walks.
#include <cstdint>
#include <vector>

#include "common/calibration.h"
#include "common/types.h"
#include "sim/imu_errors.h"
#include "sim/trajectory.h"

namespace vilslam::sim {

inline const Vec3 kGravity_W(0.0, 0.0, -9.81);

struct ImuSimConfig {
  ImuNoise noise;                             // the data sheet: densities, random walks, rate_hz (200; 400 too)
  ImuErrorRanges errors;                      // how far the true IMU may be from the data sheet (imu_errors.h)
  bool add_noise = true;                      // false: exact measurements with zero bias and no axis errors
  double initial_gyro_bias_sigma = 0.005;     // rad/s, per axis, drawn once
  double initial_accel_bias_sigma = 0.05;     // m/s^2, per axis, drawn once
  std::uint64_t seed = 0;
};

// Exact measurement of a state: gyro = omega_I, accel = R_W_I^T (a_W - g_W).
ImuSample ideal_imu(const MotionState& state);

struct ImuSimulation {
  ImuErrors errors;                           // drawn from config.errors (none without add_noise)
  std::vector<ImuSample> samples;
  std::vector<GroundTruthState> groundtruth;  // the true state and biases at every sample
};

// Samples at t0_ns + k / rate_hz up to t1_ns. The axis errors and the true noise are drawn from the seed first
// (a stream of their own, so that the noise draws of a data-sheet IMU stay those of before); noise per sample:
// sigma = density / sqrt(dt); biases walk with sigma = random_walk * sqrt(dt) per step (discrete-time model of
// Kalibr's IMU noise wiki), densities and walks the true ones.
ImuSimulation simulate_imu(const BodyMotion& motion, const ImuSimConfig& config, TimeNs t0_ns, TimeNs t1_ns);

// Ground truth (zero biases: unknown) of the motion at the given timestamps, e.g. a real IMU's.
std::vector<GroundTruthState> groundtruth_at(const BodyMotion& motion, const std::vector<TimeNs>& t_ns);

}  // namespace vilslam::sim
