#include "sim/trajectory.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace vilslam::sim {
namespace {

constexpr double kPi = 3.14159265358979323846;

// 5-point Gauss-Legendre nodes and weights on [-1, 1].
constexpr double kGaussNodes[5] = {-0.9061798459386640, -0.5384693101056831, 0.0, 0.5384693101056831,
                                   0.9061798459386640};
constexpr double kGaussWeights[5] = {0.2369268850561891, 0.4786286704993665, 0.5688888888888889, 0.4786286704993665,
                                     0.2369268850561891};

// Arc length of the curve between parameters a and b (composite Gauss-Legendre, 4 panels).
double arc_length(const UniformBSpline& curve, double a, double b) {
  constexpr int kPanels = 4;
  const double h = (b - a) / kPanels;
  double sum = 0;
  for (int p = 0; p < kPanels; ++p) {
    const double mid = a + (p + 0.5) * h;
    for (int k = 0; k < 5; ++k) sum += kGaussWeights[k] * curve.eval(mid + 0.5 * h * kGaussNodes[k]).d1.norm();
  }
  return 0.5 * h * sum;
}

// Route legs resampled at about spacing_m: the control polygon of the periodic spline.
Eigen::MatrixXd route_controls(const std::vector<Vec3>& route_W, double spacing_m) {
  if (route_W.size() < 4) throw std::invalid_argument("route needs at least 3 distinct waypoints (first == last)");
  if ((route_W.front() - route_W.back()).norm() > 1e-6) throw std::invalid_argument("route is not closed");
  std::vector<Vec3> controls;
  for (std::size_t i = 0; i + 1 < route_W.size(); ++i) {
    const Vec3 leg = route_W[i + 1] - route_W[i];
    if (leg.norm() < 1e-9) continue;
    const int pieces = std::max(1, static_cast<int>(std::ceil(leg.norm() / spacing_m)));
    for (int k = 0; k < pieces; ++k) controls.push_back(route_W[i] + leg * (static_cast<double>(k) / pieces));
  }
  if (controls.size() < 4) throw std::invalid_argument("route too short for its control spacing");
  Eigen::MatrixXd m(3, controls.size());
  for (std::size_t i = 0; i < controls.size(); ++i) m.col(static_cast<Eigen::Index>(i)) = controls[i];
  return m;
}

// Quintic smoothstep 6x^5 - 15x^4 + 10x^3 and its derivative: speed ramps with continuous acceleration.
double smootherstep(double x) { return x * x * x * (x * (6 * x - 15) + 10); }
double smootherstep_d1(double x) { return 30 * x * x * (x - 1) * (x - 1); }
// Integral of smootherstep from 0 to x.
double smootherstep_integral(double x) { return x * x * x * x * (x * (x - 3) + 2.5); }

// Body angular rate of R = Rz(yaw) Ry(pitch) Rx(roll) from the Euler angle rates.
Vec3 zyx_body_rate(double roll, double pitch, double roll_rate, double pitch_rate, double yaw_rate) {
  const double sr = std::sin(roll), cr = std::cos(roll), sp = std::sin(pitch), cp = std::cos(pitch);
  return Vec3(roll_rate - yaw_rate * sp, pitch_rate * cr + yaw_rate * sr * cp, yaw_rate * cr * cp - pitch_rate * sr);
}

Mat3 zyx_rotation(double yaw, double pitch, double roll) {
  return (Eigen::AngleAxisd(yaw, Vec3::UnitZ()) * Eigen::AngleAxisd(pitch, Vec3::UnitY()) *
          Eigen::AngleAxisd(roll, Vec3::UnitX()))
      .toRotationMatrix();
}

}  // namespace

RouteMotion::RouteMotion(const std::vector<Vec3>& route_W, const RouteMotionConfig& config)
    : config_(config), curve_(UniformBSpline::periodic(route_controls(route_W, config.control_spacing_m))) {
  if (!(config.cruise_speed_m_s > 0) || !(config.ramp_s > 0) || config.rest_start_s < 0 || config.rest_end_s < 0 ||
      config.laps < 1)
    throw std::invalid_argument("route motion: speed, ramp and laps must be positive, rests non-negative");
  const int segments = static_cast<int>(curve_.max_u());
  segment_start_length_m_.assign(segments + 1, 0.0);
  for (int i = 0; i < segments; ++i)
    segment_start_length_m_[i + 1] = segment_start_length_m_[i] + arc_length(curve_, i, i + 1);
  total_length_m_ = segment_start_length_m_.back();
  travel_m_ = config.laps * total_length_m_;
  // A route too short to reach cruise speed is flown slower: the two ramps cover v * ramp metres.
  cruise_speed_m_s_ = std::min(config.cruise_speed_m_s, travel_m_ / config.ramp_s);
  ramp_s_ = config.ramp_s;
  cruise_s_ = std::max(0.0, travel_m_ / cruise_speed_m_s_ - ramp_s_);
}

double RouteMotion::cruise_speed_for_duration(double length_m, double duration_s, const RouteMotionConfig& config) {
  // duration = rests + 2 ramps + cruise, cruise = length / v - ramp.
  const double moving_s = duration_s - config.rest_start_s - config.rest_end_s - config.ramp_s;
  if (!(moving_s > 0)) throw std::invalid_argument("duration too short for the rests and speed ramps");
  return config.laps * length_m / moving_s;
}

TimeNs RouteMotion::end_ns() const {
  return config_.start_ns + s_to_ns(config_.rest_start_s + 2 * ramp_s_ + cruise_s_ + config_.rest_end_s);
}

Eigen::Vector3d RouteMotion::distance_profile(double tau_s) const {
  const double v = cruise_speed_m_s_;
  const double t_up = config_.rest_start_s, t_cruise = t_up + ramp_s_, t_down = t_cruise + cruise_s_;
  const double t_stop = t_down + ramp_s_;
  if (tau_s <= t_up) return Eigen::Vector3d(0, 0, 0);
  if (tau_s < t_cruise) {
    const double x = (tau_s - t_up) / ramp_s_;
    return Eigen::Vector3d(v * ramp_s_ * smootherstep_integral(x), v * smootherstep(x),
                           v / ramp_s_ * smootherstep_d1(x));
  }
  if (tau_s < t_down) return Eigen::Vector3d(0.5 * v * ramp_s_ + v * (tau_s - t_cruise), v, 0);
  if (tau_s < t_stop) {
    const double y = (tau_s - t_down) / ramp_s_;
    return Eigen::Vector3d(0.5 * v * ramp_s_ + v * cruise_s_ + v * ramp_s_ * (y - smootherstep_integral(y)),
                           v * (1 - smootherstep(y)), -v / ramp_s_ * smootherstep_d1(y));
  }
  return Eigen::Vector3d(travel_m_, 0, 0);
}

double RouteMotion::length_at_parameter(double u) const {
  const int i = std::clamp(static_cast<int>(std::floor(u)), 0, static_cast<int>(segment_start_length_m_.size()) - 2);
  return segment_start_length_m_[i] + arc_length(curve_, i, u);
}

double RouteMotion::parameter_at_length(double s_m) const {
  s_m = std::clamp(s_m, 0.0, total_length_m_);
  const auto it = std::upper_bound(segment_start_length_m_.begin(), segment_start_length_m_.end(), s_m);
  const int i = std::clamp(static_cast<int>(it - segment_start_length_m_.begin()) - 1, 0,
                           static_cast<int>(segment_start_length_m_.size()) - 2);
  double lo = i, hi = i + 1;
  const double s_lo = segment_start_length_m_[i], s_hi = segment_start_length_m_[i + 1];
  double u = lo + (s_m - s_lo) / std::max(s_hi - s_lo, 1e-12);
  // Safeguarded Newton on s(u) = s_m; ds/du = |c'(u)|.
  for (int iter = 0; iter < 50; ++iter) {
    const double residual = length_at_parameter(u) - s_m;
    if (std::abs(residual) < 1e-12) break;
    (residual > 0 ? hi : lo) = u;
    const double next = u - residual / curve_.eval(u).d1.norm();
    u = (next > lo && next < hi) ? next : 0.5 * (lo + hi);
  }
  return u;
}

MotionState RouteMotion::state(TimeNs t_ns) const {
  t_ns = std::clamp(t_ns, start_ns(), end_ns());
  const Eigen::Vector3d s = distance_profile(ns_to_s(t_ns - config_.start_ns));
  // Past the first lap, the distance into the current one: the spline is periodic, so each lap starts where
  // the last ended.
  const double lap_s = s[0] <= total_length_m_ ? s[0] : s[0] - total_length_m_ * std::floor(s[0] / total_length_m_);
  const double u = parameter_at_length(lap_s);
  const SplinePoint c = curve_.eval(u);
  const Vec3 d1 = c.d1, d2 = c.d2;
  const double speed_u = d1.norm();
  // Chain rule through s(u): s' = |c'| u', s'' = (c'.c''/|c'|) u'^2 + |c'| u''.
  const double u_dot = s[1] / speed_u;
  const double u_ddot = (s[2] - d1.dot(d2) / speed_u * u_dot * u_dot) / speed_u;

  MotionState out;
  out.t_ns = t_ns;
  out.v_W = d1 * u_dot;
  out.a_W = d2 * u_dot * u_dot + d1 * u_ddot;

  const double yaw = std::atan2(d1.y(), d1.x());
  const double yaw_rate = (d1.x() * d2.y() - d1.y() * d2.x()) / (d1.x() * d1.x() + d1.y() * d1.y()) * u_dot;
  // Sway: whole periods over the route so the end orientation equals the start one.
  const double cycles = std::max(1.0, std::round(total_length_m_ / config_.sway_wavelength_m));
  const double k_roll = 2 * kPi * cycles / total_length_m_, k_pitch = 2 * k_roll;
  const double a_roll = config_.roll_amplitude_deg * kPi / 180, a_pitch = config_.pitch_amplitude_deg * kPi / 180;
  // Slopes tilt the rig nose-up: pitch = -atan2(z', h) with h = |c'_xy| (Ry positive is nose-down).
  const double h = std::hypot(d1.x(), d1.y());
  const double h_d1 = (d1.x() * d2.x() + d1.y() * d2.y()) / h;
  const double slope = -std::atan2(d1.z(), h);
  const double slope_rate = -(h * d2.z() - d1.z() * h_d1) / (h * h + d1.z() * d1.z()) * u_dot;
  const double roll = a_roll * std::sin(k_roll * s[0]);
  const double pitch = slope + a_pitch * std::sin(k_pitch * s[0]);
  const double roll_rate = a_roll * k_roll * std::cos(k_roll * s[0]) * s[1];
  const double pitch_rate = slope_rate + a_pitch * k_pitch * std::cos(k_pitch * s[0]) * s[1];
  out.T_W_I = SE3(zyx_rotation(yaw, pitch, roll), Vec3(c.value));
  out.omega_I = zyx_body_rate(roll, pitch, roll_rate, pitch_rate, yaw_rate);
  return out;
}

}  // namespace vilslam::sim
