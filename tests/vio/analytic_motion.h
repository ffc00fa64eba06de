#pragma once
// A small closed-form rig motion for the VIO unit tests: after `rest_s` seconds at rest, the position
// follows A (1 - cos(w t)) per axis and the attitude Rz(a(t)) Ry(b(t)) with a, b of the same form, so
// velocity, body rates and specific force are exact. Also a handful of landmarks seen by both cameras.
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "common/lie.h"
#include "common/types.h"
#include "frontend/stereo_match.h"
#include "vio/vision_factor.h"
#include "vio/window_state.h"

namespace vilslam::test {

struct AnalyticMotion {
  double rest_s = 0;
  Vec3 amp_m{0.8, 0.6, 0.3}, w_pos{0.9, 1.3, 1.7};
  double yaw_amp = 0.6, yaw_w = 0.7, pitch_amp = 0.2, pitch_w = 1.1;
  double gravity = 9.81;

  // x = A (1 - cos(w t)) and its first two derivatives, component-wise.
  static void wave(double A, double w, double t, double& x, double& dx, double& ddx) {
    x = A * (1 - std::cos(w * t));
    dx = A * w * std::sin(w * t);
    ddx = A * w * w * std::cos(w * t);
  }

  NavState state(double t_s) const {
    const double t = std::max(0.0, t_s - rest_s);
    NavState x;
    x.t_ns = s_to_ns(t_s);
    for (int k = 0; k < 3; ++k) {
      double p, v, a;
      wave(amp_m[k], w_pos[k], t, p, v, a);
      x.p_W_I[k] = p;
      x.v_W_m_s[k] = t_s > rest_s ? v : 0;
    }
    double yaw, dyaw, ddyaw, pitch, dpitch, ddpitch;
    wave(yaw_amp, yaw_w, t, yaw, dyaw, ddyaw);
    wave(pitch_amp, pitch_w, t, pitch, dpitch, ddpitch);
    x.R_W_I = Eigen::AngleAxisd(yaw, Vec3::UnitZ()) * Eigen::AngleAxisd(pitch, Vec3::UnitY());
    return x;
  }

  // Bias-free IMU measurement at t_s.
  ImuSample imu(double t_s) const {
    const double t = std::max(0.0, t_s - rest_s);
    const bool moving = t_s > rest_s;
    Vec3 acc_W;
    for (int k = 0; k < 3; ++k) {
      double p, v, a;
      wave(amp_m[k], w_pos[k], t, p, v, a);
      acc_W[k] = moving ? a : 0;
    }
    double yaw, dyaw, ddyaw, pitch, dpitch, ddpitch;
    wave(yaw_amp, yaw_w, t, yaw, dyaw, ddyaw);
    wave(pitch_amp, pitch_w, t, pitch, dpitch, ddpitch);
    const Mat3 Ry = Eigen::AngleAxisd(pitch, Vec3::UnitY()).toRotationMatrix();
    const Mat3 R = state(t_s).R_W_I;
    ImuSample s;
    s.t_ns = s_to_ns(t_s);
    // omega_I = Ry^T (0, 0, yaw') + (0, pitch', 0) for R = Rz(yaw) Ry(pitch).
    s.gyro_rad_s = moving ? Vec3(Ry.transpose() * Vec3(0, 0, dyaw) + Vec3(0, dpitch, 0)) : Vec3::Zero();
    s.accel_m_s2 = R.transpose() * (acc_W + Vec3(0, 0, gravity));
    return s;
  }
};

// A forward-looking stereo rig: cameras look along the IMU x axis (z_C = x_I), 11 cm baseline along -y_I.
inline StereoExtrinsics test_extrinsics() {
  Mat3 R_I_C;
  R_I_C << 0, 0, 1, -1, 0, 0, 0, -1, 0;
  return {SE3(R_I_C, Vec3(0.02, 0.0, 0.01)), SE3(R_I_C, Vec3(0.02, -0.11, 0.01))};
}

// Landmarks on a ring (radius 4-6 m, height +-2 m) around the centre of the motion, so some are in view
// whatever the yaw.
inline std::vector<Vec3> test_landmarks(int count, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> azimuth(-M_PI, M_PI), radius(4.0, 6.0), height(-2.0, 2.0);
  std::vector<Vec3> pts;
  for (int i = 0; i < count; ++i) {
    const double a = azimuth(rng), r = radius(rng);
    pts.emplace_back(0.8 + r * std::cos(a), 0.6 + r * std::sin(a), 0.3 + height(rng));
  }
  return pts;
}

// Stereo matches of the landmarks visible in both cameras (depth > 0.5 m, |x/z|, |y/z| < 0.8), with
// Gaussian noise of sigma_norm on the normalized coordinates. track_id = landmark index.
inline FrontendOutput observe(const NavState& x, const std::vector<Vec3>& landmarks, const StereoExtrinsics& extr,
                              double sigma_norm, std::mt19937& rng) {
  std::normal_distribution<double> noise(0.0, sigma_norm);
  FrontendOutput out;
  out.t_ns = x.t_ns;
  for (size_t i = 0; i < landmarks.size(); ++i) {
    const Vec3 p0 = (x.T_W_I() * extr.T_I_C0).inverse() * landmarks[i];
    const Vec3 p1 = (x.T_W_I() * extr.T_I_C1).inverse() * landmarks[i];
    const Eigen::Vector2d u0 = p0.head<2>() / p0.z(), u1 = p1.head<2>() / p1.z();
    if (p0.z() < 0.5 || p1.z() < 0.5 || u0.cwiseAbs().maxCoeff() > 0.8 || u1.cwiseAbs().maxCoeff() > 0.8) continue;
    StereoMatch m;
    m.track_id = i;
    m.left_norm = u0 + Eigen::Vector2d(noise(rng), noise(rng));
    m.right_norm = u1 + Eigen::Vector2d(noise(rng), noise(rng));
    out.matches.push_back(m);
  }
  return out;
}

}  // namespace vilslam::test
