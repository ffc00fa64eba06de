#include "vio/time_offset.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace vilslam {
namespace {

// Gyro rate at t by linear interpolation between the samples around it (imu covers t).
Vec3 gyro_at(const std::vector<ImuSample>& imu, std::size_t i, double t_ns) {
  const ImuSample& a = imu[i];
  const ImuSample& b = imu[i + 1];
  const double s = (t_ns - static_cast<double>(a.t_ns)) / static_cast<double>(b.t_ns - a.t_ns);
  return (1 - s) * a.gyro_rad_s + s * b.gyro_rad_s;
}

// Rotation vector of the gyro's rotation over [t0_ns, t1_ns]: the pieces between samples composed, each at
// its midpoint rate. nullopt when the span leaves the stream.
std::optional<Vec3> integrate_gyro(const std::vector<ImuSample>& imu, double t0_ns, double t1_ns) {
  if (imu.size() < 2 || t0_ns < imu.front().t_ns || t1_ns > imu.back().t_ns) return std::nullopt;
  auto it = std::upper_bound(imu.begin(), imu.end(), t0_ns, [](double t, const ImuSample& s) { return t < s.t_ns; });
  std::size_t i = static_cast<std::size_t>(std::max<std::ptrdiff_t>(0, (it - imu.begin()) - 1));
  Mat3 R = Mat3::Identity();
  double t = t0_ns;
  while (t < t1_ns) {
    while (i + 2 < imu.size() && imu[i + 1].t_ns <= t) ++i;
    const double end = std::min(t1_ns, static_cast<double>(imu[i + 1].t_ns));
    if (end <= t) break;
    R = R * so3::exp(gyro_at(imu, i, 0.5 * (t + end)) * ((end - t) * 1e-9));
    t = end;
  }
  return so3::log(R);
}

struct OffsetCost {
  double cost = std::numeric_limits<double>::infinity();
  Vec3 bias = Vec3::Zero();
  int intervals = 0;
};

// Residuals u_k of the header at one offset over the intervals every candidate offset can use.
OffsetCost cost_at(const std::vector<CameraRotation>& rotations, const std::vector<Vec3>& camera_in_I,
                   const std::vector<char>& usable, const std::vector<ImuSample>& imu, double offset_s) {
  std::vector<Vec3> u;
  std::vector<double> dt;
  const double offset_ns = offset_s * 1e9;
  for (std::size_t k = 0; k < rotations.size(); ++k) {
    if (!usable[k]) continue;
    const auto gyro = integrate_gyro(imu, rotations[k].t_a_ns + offset_ns, rotations[k].t_b_ns + offset_ns);
    if (!gyro) return {};
    u.push_back(*gyro - camera_in_I[k]);
    dt.push_back(ns_to_s(rotations[k].t_b_ns - rotations[k].t_a_ns));
  }
  OffsetCost out;
  Vec3 sum_dt_u = Vec3::Zero();
  double sum_dt2 = 0;
  for (std::size_t k = 0; k < u.size(); ++k) {
    sum_dt_u += dt[k] * u[k];
    sum_dt2 += dt[k] * dt[k];
  }
  out.bias = sum_dt_u / sum_dt2;
  out.cost = 0;
  for (std::size_t k = 0; k < u.size(); ++k) out.cost += (u[k] - out.bias * dt[k]).squaredNorm();
  out.intervals = static_cast<int>(u.size());
  return out;
}

}  // namespace

std::optional<TimeOffsetEstimate> estimate_cam_time_offset(const std::vector<CameraRotation>& rotations,
                                                           const std::vector<ImuSample>& imu, const Mat3& R_I_C0,
                                                           const TimeOffsetConfig& config) {
  // Intervals inside the stream whatever the offset, so every candidate is scored on the same set.
  const double margin_ns = config.max_abs_offset_s * 1e9;
  std::vector<char> usable(rotations.size(), 0);
  std::vector<Vec3> camera_in_I(rotations.size());
  double max_rate = 0;
  int count = 0;
  for (std::size_t k = 0; k < rotations.size(); ++k) {
    const CameraRotation& r = rotations[k];
    if (imu.size() < 2 || r.t_b_ns <= r.t_a_ns || r.t_a_ns - margin_ns < imu.front().t_ns ||
        r.t_b_ns + margin_ns > imu.back().t_ns)
      continue;
    usable[k] = 1;
    camera_in_I[k] = R_I_C0 * so3::log(r.R_C0a_C0b);
    max_rate = std::max(max_rate, camera_in_I[k].norm() / ns_to_s(r.t_b_ns - r.t_a_ns));
    ++count;
  }
  if (count < config.min_intervals || max_rate < config.min_rotation_rad_s) return std::nullopt;

  const int steps = static_cast<int>(std::floor(config.max_abs_offset_s / config.grid_step_s));
  std::vector<double> costs;
  int best = 0;
  for (int i = -steps; i <= steps; ++i) {
    costs.push_back(cost_at(rotations, camera_in_I, usable, imu, i * config.grid_step_s).cost);
    if (costs.back() < costs[best]) best = static_cast<int>(costs.size()) - 1;
  }
  double offset_s = (best - steps) * config.grid_step_s;
  // Parabola through the best grid point and its neighbours (not at the ends of the search range).
  if (best > 0 && best + 1 < static_cast<int>(costs.size())) {
    const double c0 = costs[best - 1], c1 = costs[best], c2 = costs[best + 1];
    const double curvature = c0 - 2 * c1 + c2;
    if (curvature > 0) offset_s += 0.5 * (c0 - c2) / curvature * config.grid_step_s;
  }
  const OffsetCost at_best = cost_at(rotations, camera_in_I, usable, imu, offset_s);
  const OffsetCost at_zero = cost_at(rotations, camera_in_I, usable, imu, 0.0);
  TimeOffsetEstimate e;
  e.offset_s = offset_s;
  e.gyro_bias_rad_s = at_best.bias;
  e.intervals = at_best.intervals;
  e.rms_rad = std::sqrt(at_best.cost / std::max(1, at_best.intervals));
  e.rms_zero_offset_rad = std::sqrt(at_zero.cost / std::max(1, at_zero.intervals));
  return e;
}

}  // namespace vilslam
