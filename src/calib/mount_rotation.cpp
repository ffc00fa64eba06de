#include "calib/mount_rotation.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include <Eigen/Eigenvalues>

namespace vilslam::calib {
namespace {

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

struct WindowRotations {
  Mat3 A;  // the IMU's turn, in I
  Mat3 B;  // the LiDAR's turn, in L
};

std::vector<WindowRotations> window_rotations(const Trajectory& T_W_I, const Trajectory& T_W_L,
                                              const MountRotationConfig& config) {
  std::vector<WindowRotations> windows;
  if (T_W_I.size() < 2 || T_W_L.size() < 2) return windows;
  const auto window_ns = static_cast<TimeNs>(config.window_s * kNsPerS);
  const auto stride_ns = static_cast<TimeNs>(config.stride_s * kNsPerS);
  const TimeNs max_gap_ns = window_ns / 4;
  const TimeNs first = std::max(T_W_I.front().t_ns, T_W_L.front().t_ns);
  const TimeNs last = std::min(T_W_I.back().t_ns, T_W_L.back().t_ns);
  for (TimeNs a = first; a + window_ns <= last; a += stride_ns) {
    const TimeNs b = a + window_ns;
    if (!covers(T_W_I, a, max_gap_ns) || !covers(T_W_I, b, max_gap_ns) || !covers(T_W_L, a, max_gap_ns) ||
        !covers(T_W_L, b, max_gap_ns)) {
      continue;
    }
    const Mat3 A = pose_at(T_W_I, a).rotation().transpose() * pose_at(T_W_I, b).rotation();
    if (so3::log(A).norm() < config.min_rotation_rad) continue;
    const Mat3 B = pose_at(T_W_L, a).rotation().transpose() * pose_at(T_W_L, b).rotation();
    windows.push_back({A, B});
  }
  return windows;
}

}  // namespace

MountRotationEstimate estimate_mount_rotation(const Trajectory& T_W_I, const Trajectory& T_W_L,
                                              const Mat3& R_I_L_nominal, const MountRotationConfig& config) {
  const std::vector<WindowRotations> windows = window_rotations(T_W_I, T_W_L, config);
  MountRotationEstimate out;
  out.R_I_L = R_I_L_nominal;
  out.windows = static_cast<int>(windows.size());
  if (windows.size() < 2) return out;
  Mat3 R = R_I_L_nominal;
  std::vector<Vec3> residuals(windows.size());
  std::vector<Mat3> jacobians(windows.size());
  std::vector<double> norms(windows.size());
  for (int it = 0; it < config.iterations; ++it) {
    // Perturbing R by Exp(eps): Exp(-eps) A' Exp(eps) ~= A' Exp((I - A'^T) eps), A' = R^T A R the IMU's turn
    // seen in L, so the residual r = Log(B^T Exp(-eps) A' Exp(eps)) ~= r0 + Jr^-1(r0) (I - A'^T) eps.
    for (std::size_t i = 0; i < windows.size(); ++i) {
      const Mat3 A_L = R.transpose() * windows[i].A * R;
      residuals[i] = so3::log(windows[i].B.transpose() * A_L);
      jacobians[i] = so3::right_jacobian_inv(residuals[i]) * (Mat3::Identity() - A_L.transpose());
      norms[i] = residuals[i].norm();
    }
    std::vector<double> sorted = norms;
    std::nth_element(sorted.begin(), sorted.begin() + static_cast<long>(sorted.size() / 2), sorted.end());
    const double scale = std::max(1.4826 * sorted[sorted.size() / 2], 1e-9);
    const double huber = config.huber_scales * scale;
    Mat3 H = Mat3::Zero();
    Vec3 g = Vec3::Zero();
    double weighted_sq = 0.0, sum_sq = 0.0;
    for (std::size_t i = 0; i < windows.size(); ++i) {
      const double w = norms[i] <= huber ? 1.0 : huber / norms[i];
      H += w * jacobians[i].transpose() * jacobians[i];
      g += w * jacobians[i].transpose() * residuals[i];
      weighted_sq += w * norms[i] * norms[i];
      sum_sq += norms[i] * norms[i];
    }
    out.rms_residual_rad = std::sqrt(sum_sq / static_cast<double>(windows.size()));
    // A-posteriori variance of one residual component, then the directions H resolves well enough.
    const double dof = std::max(3.0 * static_cast<double>(windows.size()) - 3.0, 1.0);
    const double variance = std::max(weighted_sq / dof, 1e-18);
    const Eigen::SelfAdjointEigenSolver<Mat3> eig(H);
    Vec3 step = Vec3::Zero();
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
      step -= v * (v.dot(g) / lambda);
      out.covariance_rad2 += (variance / lambda) * v * v.transpose();
    }
    if (out.estimated_directions != 2) out.kept_direction.setZero();
    R = so3::project(R * so3::exp(step));
    if (step.norm() < 1e-10) break;
  }
  out.R_I_L = R;
  out.correction_rad = so3::log(R_I_L_nominal.transpose() * R);
  return out;
}

}  // namespace vilslam::calib
