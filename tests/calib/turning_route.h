#pragma once
// A rig turning on a route, as its gyroscope and as a LiDAR on a given mount see it (the calibration tests).
#include <cmath>
#include <random>
#include <vector>

#include "common/lie.h"
#include "common/types.h"

namespace vilslam::calib::test {

constexpr double kDeg = M_PI / 180.0;

// The IMU's attitude at t: a yaw rate 0.6 rad/s * sin(0.4 t) with a roll and pitch wobble of wobble_rad
// (0 for a robot on a flat floor).
inline Mat3 attitude(double t, double wobble_rad) {
  const double yaw = -1.5 * std::cos(0.4 * t);  // integral of 0.6 sin(0.4 t)
  const Vec3 tilt(wobble_rad * std::sin(1.3 * t), wobble_rad * std::cos(0.9 * t), 0.0);
  return so3::rot_z(yaw) * so3::exp(tilt);
}

// 60 s of the route: the gyroscope at 200 Hz (body rates, plus bias_rad_s) and the IMU's poses at 10 Hz.
struct TurningRig {
  std::vector<ImuSample> imu;
  Trajectory T_W_I;
};

inline TurningRig turning_rig(double wobble_rad, const Vec3& bias_rad_s = Vec3::Zero()) {
  TurningRig rig;
  const double h = 1e-5;
  for (int k = 0; k <= 12000; ++k) {
    const double t = 0.005 * k;
    ImuSample s;
    s.t_ns = static_cast<TimeNs>(k) * 5'000'000;
    s.gyro_rad_s = so3::log(attitude(t - h, wobble_rad).transpose() * attitude(t + h, wobble_rad)) / (2 * h) + bias_rad_s;
    rig.imu.push_back(s);
    if (k % 20 == 0) rig.T_W_I.push_back({s.t_ns, SE3(attitude(t, wobble_rad), Vec3(t, 0.0, 0.0))});
  }
  return rig;
}

// The LiDAR's poses on that route with the mount R_I_L, each rotation perturbed by noise_rad per axis.
inline Trajectory lidar_route(const Trajectory& T_W_I, const Mat3& R_I_L, double noise_rad, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0.0, noise_rad);
  Trajectory out;
  for (const TimedPose& p : T_W_I) {
    const Vec3 n(noise(rng), noise(rng), noise(rng));
    out.push_back({p.t_ns, p.T_W_B * SE3(R_I_L * so3::exp(n), Vec3(0.05, 0.0, 0.2))});
  }
  return out;
}

}  // namespace vilslam::calib::test
