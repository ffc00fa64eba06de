#pragma once
// Synthetic gyro and camera rotations with a known camera-IMU time offset (tests of vio/time_offset.h and of its
// online use, pipeline/online_time_offset.h).
#include <cmath>
#include <random>
#include <vector>

#include "common/lie.h"
#include "common/time.h"
#include "vio/time_offset.h"

namespace vilslam::test {

// A rig turning about all three axes for 30 s: IMU at 200 Hz (gyro with bias and white noise) and the left
// camera's frame-to-frame rotations at 20 Hz, captured at IMU time tau and stamped tau - offset_s.
struct RotationRecording {
  std::vector<ImuSample> imu;
  std::vector<CameraRotation> rotations;
  Mat3 R_I_C0;
};

inline Vec3 body_rate(double t) {
  return Vec3(0.8 * std::sin(2 * M_PI * 0.5 * t), 0.6 * std::sin(2 * M_PI * 0.3 * t + 1.0),
              1.0 * std::sin(2 * M_PI * 0.7 * t + 2.0));
}

inline RotationRecording record_rotations(double offset_s, double rate_scale, const Vec3& bias) {
  RotationRecording r;
  r.R_I_C0 = so3::exp(Vec3(1.2, -0.4, 0.3));
  std::mt19937 rng(5);
  std::normal_distribution<double> gyro_noise(0, 0.002), camera_noise(0, 0.0005);
  // Orientation on a 1 kHz grid (midpoint integration), from which both sensors read.
  const double dt = 0.001;
  std::vector<Mat3> R_W_I{Mat3::Identity()};
  for (int i = 0; i < 32000; ++i) R_W_I.push_back(R_W_I.back() * so3::exp(rate_scale * body_rate((i + 0.5) * dt) * dt));
  for (int i = 0; i < 32000; i += 5) {
    const Vec3 noise(gyro_noise(rng), gyro_noise(rng), gyro_noise(rng));
    r.imu.push_back({s_to_ns(i * dt), rate_scale * body_rate(i * dt) + bias + noise, Vec3(0, 0, 9.81)});
  }
  const int offset_ms = static_cast<int>(std::lround(offset_s * 1000));
  for (int ms = 100; ms + 50 < 31000; ms += 50) {
    const int a = ms + offset_ms, b = ms + 50 + offset_ms;  // capture instants on the IMU clock (1 ms grid)
    const Mat3 R = (R_W_I[a] * r.R_I_C0).transpose() * (R_W_I[b] * r.R_I_C0);
    const Vec3 noise(camera_noise(rng), camera_noise(rng), camera_noise(rng));
    r.rotations.push_back({s_to_ns(ms * 1e-3), s_to_ns((ms + 50) * 1e-3), R * so3::exp(noise)});
  }
  return r;
}

}  // namespace vilslam::test
