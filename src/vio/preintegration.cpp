#include "vio/preintegration.h"

#include <algorithm>
#include <iterator>
#include <stdexcept>

namespace vilslam {

Preintegration::Preintegration(const Vec3& bias_gyro_rad_s, const Vec3& bias_accel_m_s2, const ImuNoise& noise)
    : bias_gyro_(bias_gyro_rad_s), bias_accel_(bias_accel_m_s2), noise_(noise) {}

void Preintegration::integrate(const Vec3& gyro_rad_s, const Vec3& accel_m_s2, double dt_s, double held_rate_sigma_rad_s,
                               double held_accel_sigma_m_s2) {
  if (dt_s <= 0) return;
  const Vec3 omega = gyro_rad_s - bias_gyro_;
  const Vec3 acc = accel_m_s2 - bias_accel_;
  const Mat3 dR_step = so3::exp(omega * dt_s);
  const Mat3 Jr_step = so3::right_jacobian(omega * dt_s);
  const Mat3 acc_hat = so3::hat(acc);
  const double dt2 = dt_s * dt_s;

  // Noise propagation, eq. (62)-(63): A eta_k + B eta_gd + C eta_ad with ordering [dphi, dv, dp].
  Mat9 A = Mat9::Identity();
  A.block<3, 3>(0, 0) = dR_step.transpose();
  A.block<3, 3>(3, 0) = -delta_R_ * acc_hat * dt_s;
  A.block<3, 3>(6, 0) = -0.5 * delta_R_ * acc_hat * dt2;
  A.block<3, 3>(6, 3) = Mat3::Identity() * dt_s;
  Eigen::Matrix<double, 9, 6> B = Eigen::Matrix<double, 9, 6>::Zero();
  B.block<3, 3>(0, 0) = Jr_step * dt_s;
  B.block<3, 3>(3, 3) = delta_R_ * dt_s;
  B.block<3, 3>(6, 3) = 0.5 * delta_R_ * dt2;
  // Discrete-time noise covariance from the continuous densities: sigma_d^2 = sigma^2 / dt; a held
  // measurement's own error is constant over the step, so its variance is added as it is.
  Eigen::Matrix<double, 6, 1> q;
  q << Vec3::Constant(noise_.gyro_noise_density * noise_.gyro_noise_density / dt_s +
                      held_rate_sigma_rad_s * held_rate_sigma_rad_s),
      Vec3::Constant(noise_.accel_noise_density * noise_.accel_noise_density / dt_s +
                     held_accel_sigma_m_s2 * held_accel_sigma_m_s2);
  covariance_ = A * covariance_ * A.transpose() + B * q.asDiagonal() * B.transpose();

  // Bias Jacobians, Appendix B eq. (69)-(70); positions and velocities use the values before this step.
  dp_dba_ += dv_dba_ * dt_s - 0.5 * delta_R_ * dt2;
  dp_dbg_ += dv_dbg_ * dt_s - 0.5 * delta_R_ * acc_hat * dR_dbg_ * dt2;
  dv_dba_ -= delta_R_ * dt_s;
  dv_dbg_ -= delta_R_ * acc_hat * dR_dbg_ * dt_s;
  dR_dbg_ = dR_step.transpose() * dR_dbg_ - Jr_step * dt_s;

  // Deltas, eq. (38) written recursively (Euler).
  delta_p_ += delta_v_ * dt_s + 0.5 * delta_R_ * acc * dt2;
  delta_v_ += delta_R_ * acc * dt_s;
  delta_R_ = so3::project(delta_R_ * dR_step);
  dt_s_ += dt_s;
}

// eq. (44).
Mat3 Preintegration::corrected_delta_R(const Vec3& bias_gyro_rad_s) const {
  return delta_R_ * so3::exp(dR_dbg_ * (bias_gyro_rad_s - bias_gyro_));
}

Vec3 Preintegration::corrected_delta_v(const Vec3& bias_gyro_rad_s, const Vec3& bias_accel_m_s2) const {
  return delta_v_ + dv_dbg_ * (bias_gyro_rad_s - bias_gyro_) + dv_dba_ * (bias_accel_m_s2 - bias_accel_);
}

Vec3 Preintegration::corrected_delta_p(const Vec3& bias_gyro_rad_s, const Vec3& bias_accel_m_s2) const {
  return delta_p_ + dp_dbg_ * (bias_gyro_rad_s - bias_gyro_) + dp_dba_ * (bias_accel_m_s2 - bias_accel_);
}

namespace {

// Measurement at time t: linear interpolation between the samples bracketing t, nearest sample outside.
ImuSample sample_at(const std::vector<ImuSample>& samples, TimeNs t_ns) {
  const auto it = std::lower_bound(samples.begin(), samples.end(), t_ns,
                                   [](const ImuSample& s, TimeNs t) { return s.t_ns < t; });
  if (it == samples.begin()) return samples.front();
  if (it == samples.end()) return samples.back();
  const ImuSample& b = *it;
  const ImuSample& a = *(it - 1);
  const double alpha = static_cast<double>(t_ns - a.t_ns) / static_cast<double>(b.t_ns - a.t_ns);
  ImuSample s;
  s.t_ns = t_ns;
  s.gyro_rad_s = (1 - alpha) * a.gyro_rad_s + alpha * b.gyro_rad_s;
  s.accel_m_s2 = (1 - alpha) * a.accel_m_s2 + alpha * b.accel_m_s2;
  return s;
}

}  // namespace

double integrate_samples(const std::vector<ImuSample>& samples, TimeNs t0_ns, TimeNs t1_ns, Preintegration& preint,
                         const ImuGapModel& gap) {
  if (samples.empty()) throw std::invalid_argument("integrate_samples: no IMU samples");
  if (t1_ns < t0_ns) throw std::invalid_argument("integrate_samples: t1 before t0");
  // Step boundaries: t0, every sample time strictly inside (t0, t1), t1.
  TimeNs a = t0_ns;
  double gap_s = 0;
  auto it = first_sample_after(samples, t0_ns);
  while (a < t1_ns) {
    const TimeNs b = (it != samples.end() && it->t_ns < t1_ns) ? it->t_ns : t1_ns;
    const ImuSample mid = sample_at(samples, a + (b - a) / 2);
    // The sample interval holding this step: [previous sample, it] (it is the first sample after a).
    const bool in_gap = it != samples.begin() && it != samples.end() &&
                        ns_to_s(it->t_ns - std::prev(it)->t_ns) > gap.max_step_s;
    if (in_gap) {
      gap_s += ns_to_s(b - a);
      preint.integrate(mid.gyro_rad_s, mid.accel_m_s2, ns_to_s(b - a), gap.rate_sigma_rad_s, gap.accel_sigma_m_s2);
    } else {
      preint.integrate(mid.gyro_rad_s, mid.accel_m_s2, ns_to_s(b - a));
    }
    a = b;
    if (it != samples.end()) ++it;
  }
  return gap_s;
}

std::vector<ImuSample>::const_iterator first_sample_after(const std::vector<ImuSample>& samples, TimeNs t_ns) {
  return std::upper_bound(samples.begin(), samples.end(), t_ns, [](TimeNs t, const ImuSample& s) { return t < s.t_ns; });
}

std::vector<ImuSample> samples_for_frame(const std::vector<ImuSample>& samples, TimeNs t_ns, double max_step_s) {
  auto end = first_sample_after(samples, t_ns);
  if (end != samples.end() && end != samples.begin() && ns_to_s(end->t_ns - std::prev(end)->t_ns) > max_step_s) ++end;
  return {samples.begin(), end};
}

void drop_samples_before(std::vector<ImuSample>& samples, TimeNs t_ns) {
  const auto first_after = first_sample_after(samples, t_ns);
  if (first_after != samples.begin()) samples.erase(samples.begin(), first_after - 1);
}

}  // namespace vilslam
