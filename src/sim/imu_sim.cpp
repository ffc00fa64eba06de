#include "sim/imu_sim.h"

#include <cmath>
#include <random>
#include <stdexcept>

namespace vilslam::sim {
namespace {

constexpr std::uint64_t kAxisErrorStream = 0x1A5E77E5C0FFEEull;  // seeds the axis errors apart from the noise

Vec3 gaussian3(std::mt19937_64& rng, double sigma) {
  std::normal_distribution<double> n(0.0, 1.0);
  const double x = n(rng), y = n(rng), z = n(rng);
  return sigma * Vec3(x, y, z);
}

GroundTruthState truth_of(const MotionState& state) {
  GroundTruthState gt;
  gt.t_ns = state.t_ns;
  gt.T_W_I = state.T_W_I;
  gt.v_W_m_s = state.v_W;
  return gt;
}

}  // namespace

ImuSample ideal_imu(const MotionState& state) {
  ImuSample s;
  s.t_ns = state.t_ns;
  s.gyro_rad_s = state.omega_I;
  s.accel_m_s2 = state.T_W_I.quat().conjugate() * (state.a_W - kGravity_W);
  return s;
}

ImuSimulation simulate_imu(const BodyMotion& motion, const ImuSimConfig& config, TimeNs t0_ns, TimeNs t1_ns) {
  if (!(config.noise.rate_hz > 0)) throw std::invalid_argument("IMU rate must be positive");
  const double dt = 1.0 / config.noise.rate_hz;
  std::mt19937_64 rng(config.seed);
  ImuSimulation out;
  out.errors.noise = config.noise;
  Vec3 bias_gyro = Vec3::Zero(), bias_accel = Vec3::Zero();
  if (config.add_noise) {
    out.errors = draw_imu_errors(config.noise, config.errors, config.seed ^ kAxisErrorStream);
    bias_gyro = gaussian3(rng, config.initial_gyro_bias_sigma);
    bias_accel = gaussian3(rng, config.initial_accel_bias_sigma);
  }
  const ImuNoise& noise = out.errors.noise;
  const double gyro_sigma = noise.gyro_noise_density / std::sqrt(dt);
  const double accel_sigma = noise.accel_noise_density / std::sqrt(dt);
  const double gyro_walk = noise.gyro_random_walk * std::sqrt(dt);
  const double accel_walk = noise.accel_random_walk * std::sqrt(dt);

  for (long k = 0;; ++k) {
    const TimeNs t_ns = t0_ns + s_to_ns(k * dt);
    if (t_ns > t1_ns) break;
    const MotionState state = motion.state(t_ns);
    ImuSample sample = ideal_imu(state);
    GroundTruthState gt = truth_of(state);
    if (config.add_noise) {
      sample = apply_axis_errors(out.errors, sample);
      sample.gyro_rad_s += bias_gyro + gaussian3(rng, gyro_sigma);
      sample.accel_m_s2 += bias_accel + gaussian3(rng, accel_sigma);
      gt.bias_gyro_rad_s = bias_gyro;
      gt.bias_accel_m_s2 = bias_accel;
      bias_gyro += gaussian3(rng, gyro_walk);
      bias_accel += gaussian3(rng, accel_walk);
    }
    out.samples.push_back(sample);
    out.groundtruth.push_back(gt);
  }
  return out;
}

std::vector<GroundTruthState> groundtruth_at(const BodyMotion& motion, const std::vector<TimeNs>& t_ns) {
  std::vector<GroundTruthState> out;
  out.reserve(t_ns.size());
  for (const TimeNs t : t_ns) out.push_back(truth_of(motion.state(t)));
  return out;
}

}  // namespace vilslam::sim
