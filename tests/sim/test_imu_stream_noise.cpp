#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>

#include "sim/imu_sim.h"
#include "sim/imu_stream_noise.h"

namespace vilslam::sim {
namespace {

// A 6 m square at 1.2 m/s: four turns, the sway, speed ramps and rests at both ends (about 30 s).
RouteMotion square_motion() {
  return RouteMotion({Vec3(0, 0, 1.2), Vec3(6, 0, 1.2), Vec3(6, 6, 1.2), Vec3(0, 6, 1.2), Vec3(0, 0, 1.2)},
                     RouteMotionConfig{});
}

// A stream with known white noise (V1_01's order: a MAV's vibration) on a smooth motion: the Allan
// deviation at the sample interval recovers both densities within 10 %, at 200 and 400 Hz, also when a
// second of samples is missing; the random walks stay the datasheet's.
TEST(ImuStreamNoise, RecoversTheWhiteNoiseDensityOfASyntheticStream) {
  const RouteMotion motion = square_motion();
  const ImuNoise datasheet;
  for (const double rate_hz : {200.0, 400.0}) {
    ImuSimConfig config;
    config.noise.gyro_noise_density = 2.5e-3;
    config.noise.accel_noise_density = 6.0e-2;
    config.noise.rate_hz = rate_hz;
    config.seed = 7;
    ImuSimulation sim = simulate_imu(motion, config, motion.start_ns(), motion.end_ns());
    const ImuNoise& truth = sim.errors.noise;  // the drawn true noise (imu_errors.h), not the configured one
    std::vector<ImuSample> samples = std::move(sim.samples);
    const TimeNs gap_start = motion.start_ns() + s_to_ns(10.0), gap_end = gap_start + kNsPerSecond;
    const auto in_gap = [&](const ImuSample& s) { return s.t_ns >= gap_start && s.t_ns < gap_end; };
    samples.erase(std::remove_if(samples.begin(), samples.end(), in_gap), samples.end());
    const ImuNoise estimate = noise_from_stream(samples, datasheet);
    const double gyro_ratio = estimate.gyro_noise_density / truth.gyro_noise_density;
    const double accel_ratio = estimate.accel_noise_density / truth.accel_noise_density;
    std::cout << rate_hz << " Hz, " << samples.size() << " samples: estimated / true density gyro " << gyro_ratio
              << ", accel " << accel_ratio << "\n";
    EXPECT_NEAR(gyro_ratio, 1.0, 0.1);
    EXPECT_NEAR(accel_ratio, 1.0, 0.1);
    EXPECT_EQ(estimate.gyro_random_walk, datasheet.gyro_random_walk);
    EXPECT_EQ(estimate.accel_random_walk, datasheet.accel_random_walk);
    EXPECT_EQ(estimate.rate_hz, datasheet.rate_hz);
  }
}

// An exact stream at rest and a too short one keep the datasheet densities: never below them. Moving, an
// exact stream reads only the motion term (s' tau0)^2 / 2: on the square's turns at 200 Hz above the
// ADIS16448 datasheet, but a small part of a MAV's vibration (V1_01: gyro 2.6e-3, accel 7.7e-2).
TEST(ImuStreamNoise, NeverBelowTheDatasheetAndTheMotionTermIsSmall) {
  const RouteMotion motion = square_motion();
  ImuSimConfig config;
  config.add_noise = false;
  const std::vector<ImuSample> exact = simulate_imu(motion, config, motion.start_ns(), motion.end_ns()).samples;
  const ImuNoise datasheet;
  const std::vector<ImuSample> at_rest(exact.begin(), exact.begin() + 100);  // the first 0.5 s
  const ImuNoise rest = noise_from_stream(at_rest, datasheet);
  EXPECT_EQ(rest.gyro_noise_density, datasheet.gyro_noise_density);
  EXPECT_EQ(rest.accel_noise_density, datasheet.accel_noise_density);
  const std::vector<ImuSample> short_stream(exact.begin(), exact.begin() + 5);
  EXPECT_EQ(allan_deviation_at_sample_interval(short_stream).pairs, 4u);
  EXPECT_EQ(allan_deviation_at_sample_interval({}).pairs, 0u);

  const ImuNoise moving = noise_from_stream(exact, datasheet);
  std::cout << "exact stream on the square: gyro " << moving.gyro_noise_density << " rad/s/sqrt(Hz), accel "
            << moving.accel_noise_density << " m/s^2/sqrt(Hz)\n";
  EXPECT_GE(moving.gyro_noise_density, datasheet.gyro_noise_density);
  EXPECT_LT(moving.gyro_noise_density, 0.15 * 2.6e-3);
  EXPECT_LT(moving.accel_noise_density, 0.15 * 7.7e-2);
}

}  // namespace
}  // namespace vilslam::sim
