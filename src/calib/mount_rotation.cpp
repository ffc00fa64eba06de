#include "calib/mount_rotation.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>

#include "vio/preintegration.h"

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
  TimeNs a_ns = 0, b_ns = 0;
  Mat3 B;          // the LiDAR's turn, in L
  bool turning = false;
};

// The gyroscope's rotation over the window less `bias` (vio/preintegration.h; the accelerometer's part is not
// used). Its delta_R is A, and A(bias + d) ~= A Exp(dR_dbg d).
Preintegration gyro_turn(const std::vector<ImuSample>& imu, const Window& w, const Vec3& bias, double* gap_s = nullptr) {
  Preintegration turn(bias, Vec3::Zero(), ImuNoise{});
  const double in_gaps_s = integrate_samples(imu, w.a_ns, w.b_ns, turn, ImuGapModel{ns_to_s(w.b_ns - w.a_ns) / 4});
  if (gap_s) *gap_s = in_gaps_s;
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
  for (TimeNs a = first; a + window_ns <= last; a += stride_ns) {
    Window w;
    w.a_ns = a;
    w.b_ns = a + window_ns;
    if (!covers(T_W_L, w.a_ns, max_gap_ns) || !covers(T_W_L, w.b_ns, max_gap_ns)) continue;
    double gap_s = 0.0;
    const Preintegration turn = gyro_turn(imu, w, Vec3::Zero(), &gap_s);
    if (gap_s > 0.0) continue;
    w.turning = so3::log(turn.delta_R()).norm() >= config.min_rotation_rad;
    w.B = pose_at(T_W_L, w.a_ns).rotation().transpose() * pose_at(T_W_L, w.b_ns).rotation();
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
  for (const Window& w : windows) out.turning_windows += w.turning ? 1 : 0;
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
      const Preintegration turn = gyro_turn(imu, windows[i], bias);
      const Mat3 A_L = R.transpose() * turn.delta_R() * R;
      residuals[i] = so3::log(windows[i].B.transpose() * A_L);
      const Mat3 Jr_inv = so3::right_jacobian_inv(residuals[i]);
      jacobians[i] << Jr_inv * (Mat3::Identity() - A_L.transpose()), Jr_inv * R.transpose() * turn.dR_dbg();
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
      if (windows[i].turning) turning_sq += norms[i] * norms[i];
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
