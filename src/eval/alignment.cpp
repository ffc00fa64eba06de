#include "eval/alignment.h"

#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace vilslam::eval {
namespace {

Vec3 mean_of(const std::vector<Vec3>& points) {
  Vec3 sum = Vec3::Zero();
  for (const Vec3& p : points) sum += p;
  return sum / static_cast<double>(points.size());
}

// Umeyama, "Least-squares estimation of transformation parameters between two point patterns",
// PAMI 1991: covariance eq. (38), rotation eq. (40) with S of eq. (43), scale eq. (42), translation eq. (41).
Alignment umeyama(const std::vector<Vec3>& x, const std::vector<Vec3>& y, bool with_scale) {
  const double n = static_cast<double>(x.size());
  const Vec3 mean_x = mean_of(x);
  const Vec3 mean_y = mean_of(y);
  double sigma_x = 0;
  Mat3 cov = Mat3::Zero();
  for (std::size_t i = 0; i < x.size(); ++i) {
    sigma_x += (x[i] - mean_x).squaredNorm();
    cov += (y[i] - mean_y) * (x[i] - mean_x).transpose();
  }
  sigma_x /= n;
  cov /= n;
  Eigen::JacobiSVD<Mat3> svd(cov, Eigen::ComputeFullU | Eigen::ComputeFullV);
  const Vec3 d = svd.singularValues();
  if ((d.array() > std::numeric_limits<double>::epsilon()).count() < 2) {
    throw std::invalid_argument("degenerate point set: Umeyama alignment is not possible");
  }
  Mat3 S = Mat3::Identity();
  if (svd.matrixU().determinant() * svd.matrixV().determinant() < 0) S(2, 2) = -1;
  const Mat3 R = svd.matrixU() * S * svd.matrixV().transpose();
  Alignment a;
  a.mode = with_scale ? AlignMode::kSim3 : AlignMode::kSe3;
  a.scale = with_scale ? (d.asDiagonal() * S).trace() / sigma_x : 1.0;
  a.T_gt_est = SE3(R, mean_y - a.scale * R * mean_x);
  return a;
}

// Yaw maximizing sum y_c^T Rz(theta) x_c over centred points: theta = atan2(sum(x_c × y_c)_z, sum x_c·y_c in xy).
Alignment position_yaw(const std::vector<Vec3>& x, const std::vector<Vec3>& y) {
  const Vec3 mean_x = mean_of(x);
  const Vec3 mean_y = mean_of(y);
  double sin_sum = 0, cos_sum = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    const Vec3 xc = x[i] - mean_x;
    const Vec3 yc = y[i] - mean_y;
    sin_sum += xc.x() * yc.y() - xc.y() * yc.x();
    cos_sum += xc.x() * yc.x() + xc.y() * yc.y();
  }
  if (std::hypot(sin_sum, cos_sum) <= std::numeric_limits<double>::epsilon()) {
    throw std::invalid_argument("degenerate point set: yaw alignment is not possible");
  }
  const Mat3 R = Eigen::AngleAxisd(std::atan2(sin_sum, cos_sum), Vec3::UnitZ()).toRotationMatrix();
  Alignment a;
  a.mode = AlignMode::kPosYaw;
  a.T_gt_est = SE3(R, mean_y - R * mean_x);
  return a;
}

}  // namespace

AlignMode parse_align_mode(const std::string& name) {
  if (name == "se3") return AlignMode::kSe3;
  if (name == "sim3") return AlignMode::kSim3;
  if (name == "posyaw") return AlignMode::kPosYaw;
  if (name == "none") return AlignMode::kNone;
  throw std::invalid_argument("unknown alignment '" + name + "' (se3, sim3, posyaw or none)");
}

std::string align_mode_name(AlignMode mode) {
  switch (mode) {
    case AlignMode::kSe3:
      return "se3";
    case AlignMode::kSim3:
      return "sim3";
    case AlignMode::kPosYaw:
      return "posyaw";
    case AlignMode::kNone:
      return "none";
  }
  return "none";
}

Alignment align_positions(const std::vector<Vec3>& p_est, const std::vector<Vec3>& p_gt, AlignMode mode) {
  if (p_est.size() != p_gt.size()) throw std::invalid_argument("alignment needs equally many points");
  if (p_est.empty()) throw std::invalid_argument("alignment needs at least one point pair");
  switch (mode) {
    case AlignMode::kSe3:
      return umeyama(p_est, p_gt, false);
    case AlignMode::kSim3:
      return umeyama(p_est, p_gt, true);
    case AlignMode::kPosYaw:
      return position_yaw(p_est, p_gt);
    case AlignMode::kNone:
      break;
  }
  return Alignment{};
}

Alignment align_trajectories(const Trajectory& est, const Trajectory& gt, AlignMode mode, std::size_t first_n) {
  if (est.size() != gt.size()) throw std::invalid_argument("alignment needs matched trajectories");
  const std::size_t n = first_n == 0 ? est.size() : std::min(first_n, est.size());
  std::vector<Vec3> p_est, p_gt;
  for (std::size_t i = 0; i < n; ++i) {
    p_est.push_back(est[i].T_W_B.translation());
    p_gt.push_back(gt[i].T_W_B.translation());
  }
  return align_positions(p_est, p_gt, mode);
}

Trajectory apply_alignment(const Trajectory& est, const Alignment& a) {
  Trajectory out;
  out.reserve(est.size());
  const Quat& q_a = a.T_gt_est.quat();
  for (const TimedPose& p : est) {
    const Vec3 t = q_a * (a.scale * p.T_W_B.translation()) + a.T_gt_est.translation();
    out.push_back({p.t_ns, SE3(q_a * p.T_W_B.quat(), t)});
  }
  return out;
}

}  // namespace vilslam::eval
