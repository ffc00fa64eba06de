#pragma once
// A rig turning on a route, as the IMU and as a LiDAR on a given mount sees it (the calibration tests).
#include <cmath>
#include <random>

#include "common/lie.h"
#include "common/types.h"

namespace vilslam::calib::test {

constexpr double kDeg = M_PI / 180.0;

// A rig driving a figure of turns at 10 Hz for 60 s: yaw rate 0.6 rad/s * sin(0.4 t), with a roll and pitch
// wobble of `wobble_rad` (0 for a robot on a flat floor).
inline Trajectory imu_route(double wobble_rad) {
  Trajectory out;
  for (int k = 0; k <= 600; ++k) {
    const double t = 0.1 * k;
    const double yaw = -1.5 * std::cos(0.4 * t);  // integral of 0.6 sin(0.4 t)
    const Vec3 tilt(wobble_rad * std::sin(1.3 * t), wobble_rad * std::cos(0.9 * t), 0.0);
    const Mat3 R = so3::rot_z(yaw) * so3::exp(tilt);
    out.push_back({static_cast<TimeNs>(k) * 100'000'000, SE3(R, Vec3(t, 0.0, 0.0))});
  }
  return out;
}

// The LiDAR's poses on that route with the mount R_I_L, each rotation perturbed by noise_rad per axis.
inline Trajectory lidar_route(const Trajectory& imu, const Mat3& R_I_L, double noise_rad, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0.0, noise_rad);
  Trajectory out;
  for (const TimedPose& p : imu) {
    const Vec3 n(noise(rng), noise(rng), noise(rng));
    out.push_back({p.t_ns, p.T_W_B * SE3(R_I_L * so3::exp(n), Vec3(0.05, 0.0, 0.2))});
  }
  return out;
}

}  // namespace vilslam::calib::test
