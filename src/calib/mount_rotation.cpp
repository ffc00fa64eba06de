#include "calib/mount_rotation.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>

namespace vilslam::calib {
namespace {

using Mat36 = Eigen::Matrix<double, 3, 6>;
using Mat6 = Eigen::Matrix<double, 6, 6>;
using Vec6 = Eigen::Matrix<double, 6, 1>;

constexpr double kNsPerS = 1e9;

// A trajectory covers t when it has a pose within max_gap_ns on each side (no interpolation across a gap).
bool covers(const Trajectory& poses, TimeNs t_ns, TimeNs max_gap_ns) {
  const auto after = std::lower_bound(poses.begin(), poses.end(), t_ns,
                                      [](const TimedPose& p, TimeNs t) { return p.t_ns < t; });
  if (after == poses.end()) return false;
  if (after->t_ns == t_ns) return true;
  if (after == poses.begin()) return false;
  return after->t_ns - (after - 1)->t_ns <= max_gap_ns;
}

struct Window {
  std::size_t first_sample = 0, end_sample = 0;  // IMU samples [first, end) span [a, b]
  TimeNs a_ns = 0, b_ns = 0;
  Mat3 B;  // the LiDAR's turn, in L
};

// The gyroscope's rotation over [a, b] less `bias`, and its first-order change with the bias:
// A(bias + d) ~= A Exp(J d), accumulated as J <- dR^T J - Jr(w dt) dt (Forster et al. 2017, eq. (44)).
struct GyroTurn {
  Mat3 A = Mat3::Identity();
  Mat3 J_bias = Mat3::Zero();
};

GyroTurn integrate_gyro(const std::vector<ImuSample>& imu, const Window& w, const Vec3& bias) {
  GyroTurn turn;
  for (std::size_t k = w.first_sample; k + 1 < w.end_sample; ++k) {
    const TimeNs from = std::max(imu[k].t_ns, w.a_ns);
    const TimeNs to = std::min(imu[k + 1].t_ns, w.b_ns);
    if (to <= from) continue;
    const double dt = static_cast<double>(to - from) / kNsPerS;
    const Vec3 phi = (0.5 * (imu[k].gyro_rad_s + imu[k + 1].gyro_rad_s) - bias) * dt;
    const Mat3 dR = so3::exp(phi);
    turn.J_bias = dR.transpose() * turn.J_bias - so3::right_jacobian(phi) * dt;
    turn.A = turn.A * dR;
  }
  return turn;
}

std::vector<Window> windows_of(const std::vector<ImuSample>& imu, const Trajectory& T_W_L,
                               const MountRotationConfig& config) {
  std::vector<Window> windows;
  if (imu.size() < 2 || T_W_L.size() < 2) return windows;
  const auto window_ns = static_cast<TimeNs>(config.window_s * kNsPerS);
  const auto stride_ns = static_cast<TimeNs>(config.stride_s * kNsPerS);
  const TimeNs max_gap_ns = window_ns / 4;
  const TimeNs first = std::max(imu.front().t_ns, T_W_L.front().t_ns);
  const TimeNs last = std::min(imu.back().t_ns, T_W_L.back().t_ns);
  const auto before = [](const ImuSample& s, TimeNs t) { return s.t_ns < t; };
  for (TimeNs a = first; a + window_ns <= last; a += stride_ns) {
    const TimeNs b = a + window_ns;
    if (!covers(T_W_L, a, max_gap_ns) || !covers(T_W_L, b, max_gap_ns)) continue;
    Window w;
    w.a_ns = a;
    w.b_ns = b;
    // The last sample at or before a, through the first at or after b.
    auto lo = std::lower_bound(imu.begin(), imu.end(), a, before);
    if (lo == imu.end()) continue;
    if (lo->t_ns > a) {
      if (lo == imu.begin()) continue;
      --lo;
    }
    const auto hi = std::lower_bound(lo, imu.end(), b, before);
    if (hi == imu.end()) continue;
    bool gap = false;
    for (auto it = lo; it != hi && !gap; ++it) gap = (it + 1)->t_ns - it->t_ns > max_gap_ns;
    if (gap) continue;
    w.first_sample = static_cast<std::size_t>(lo - imu.begin());
    w.end_sample = static_cast<std::size_t>(hi - imu.begin()) + 1;
    w.B = pose_at(T_W_L, a).rotation().transpose() * pose_at(T_W_L, b).rotation();
    windows.push_back(w);
  }
  return windows;
}

}  // namespace

MountRotationEstimate estimate_mount_rotation(const std::vector<ImuSample>& imu, const Trajectory& T_W_L,
                                              const Mat3& R_I_L_nominal, const MountRotationConfig& config) {
  const std::vector<Window> windows = windows_of(imu, T_W_L, config);
  MountRotationEstimate out;
  out.R_I_L = R_I_L_nominal;
  out.windows = static_cast<int>(windows.size());
  std::vector<bool> turning(windows.size());
  for (std::size_t i = 0; i < windows.size(); ++i) {
    turning[i] = so3::log(integrate_gyro(imu, windows[i], Vec3::Zero()).A).norm() >= config.min_rotation_rad;
    out.turning_windows += turning[i] ? 1 : 0;
  }
  if (out.turning_windows == 0) return out;
  Mat3 R = R_I_L_nominal;
  Vec3 bias = Vec3::Zero();
  std::vector<Vec3> residuals(windows.size());
  std::vector<Mat36> jacobians(windows.size());
  std::vector<double> norms(windows.size());
  for (int it = 0; it < config.iterations; ++it) {
    // Perturbing R by Exp(eps) and the bias by d: Exp(-eps) A' Exp(eps) ~= A' Exp((I - A'^T) eps + R^T J d),
    // A' = R^T A R the IMU's turn seen in L, so r = Log(B^T Exp(-eps) A' Exp(eps)) ~= r0 + Jr^-1(r0) [..] [eps; d].
    for (std::size_t i = 0; i < windows.size(); ++i) {
      const GyroTurn turn = integrate_gyro(imu, windows[i], bias);
      const Mat3 A_L = R.transpose() * turn.A * R;
      residuals[i] = so3::log(windows[i].B.transpose() * A_L);
      const Mat3 Jr_inv = so3::right_jacobian_inv(residuals[i]);
      jacobians[i] << Jr_inv * (Mat3::Identity() - A_L.transpose()), Jr_inv * R.transpose() * turn.J_bias;
      norms[i] = residuals[i].norm();
    }
    std::vector<double> sorted = norms;
    std::nth_element(sorted.begin(), sorted.begin() + static_cast<long>(sorted.size() / 2), sorted.end());
    const double huber = config.huber_scales * std::max(1.4826 * sorted[sorted.size() / 2], 1e-9);
    Mat6 H = Mat6::Zero();
    Vec6 g = Vec6::Zero();
    double weighted_sq = 0.0, turning_sq = 0.0;
    for (std::size_t i = 0; i < windows.size(); ++i) {
      const double w = norms[i] <= huber ? 1.0 : huber / norms[i];
      H += w * jacobians[i].transpose() * jacobians[i];
      g += w * jacobians[i].transpose() * residuals[i];
      weighted_sq += w * norms[i] * norms[i];
      if (turning[i]) turning_sq += norms[i] * norms[i];
    }
    out.rms_residual_rad = std::sqrt(turning_sq / out.turning_windows);
    // The bias is seen by every window: eliminate it (Schur complement), then update only the mount's
    // directions the turns resolve to max_sigma_rad, with the a-posteriori variance of one residual component.
    const Mat3 H_bb = H.bottomRightCorner<3, 3>() + 1e-12 * Mat3::Identity();
    const Eigen::LDLT<Mat3> H_bb_ldlt(H_bb);
    const Mat3 S = H.topLeftCorner<3, 3>() - H.topRightCorner<3, 3>() * H_bb_ldlt.solve(H.bottomLeftCorner<3, 3>());
    const Vec3 g_s = g.head<3>() - H.topRightCorner<3, 3>() * H_bb_ldlt.solve(g.tail<3>());
    // Windows overlapping window_s / stride_s times share their noise: count them as that many times fewer.
    const double dof = std::max(3.0 * static_cast<double>(windows.size()) - 6.0, 1.0);
    const double overlap = std::max(1.0, config.window_s / config.stride_s);
    const double variance = std::max(overlap * weighted_sq / dof, 1e-18);
    const Eigen::SelfAdjointEigenSolver<Mat3> eig(S);
    Vec3 eps = Vec3::Zero();
    out.covariance_rad2.setZero();
    out.estimated_directions = 0;
    for (int k = 0; k < 3; ++k) {
      const double lambda = eig.eigenvalues()(k);
      const Vec3 v = eig.eigenvectors().col(k);
      if (lambda <= 0.0 || variance / lambda > config.max_sigma_rad * config.max_sigma_rad) {
        out.kept_direction = v;
        continue;
      }
      ++out.estimated_directions;
      eps -= v * (v.dot(g_s) / lambda);
      out.covariance_rad2 += (variance / lambda) * v * v.transpose();
    }
    if (out.estimated_directions != 2) out.kept_direction.setZero();
    const Vec3 d_bias = -H_bb_ldlt.solve(g.tail<3>() + H.bottomLeftCorner<3, 3>() * eps);
    R = so3::project(R * so3::exp(eps));
    bias += d_bias;
    if (eps.norm() < 1e-10 && d_bias.norm() < 1e-10) break;
  }
  out.R_I_L = R;
  out.correction_rad = so3::log(R_I_L_nominal.transpose() * R);
  out.gyro_bias_rad_s = bias;
  return out;
}

}  // namespace vilslam::calib
