#include "eval/kitti_metric.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

namespace vilslam::eval {
namespace {

constexpr std::size_t kStepFrames = 10;
constexpr double kLengthsM[] = {100, 200, 300, 400, 500, 600, 700, 800};

std::vector<double> accumulated_distances(const Trajectory& traj) {
  std::vector<double> dist(traj.size(), 0.0);
  for (std::size_t i = 1; i < traj.size(); ++i) {
    dist[i] = dist[i - 1] + (traj[i].T_W_B.translation() - traj[i - 1].T_W_B.translation()).norm();
  }
  return dist;
}

// Devkit rotationError: acos of 0.5 (trace - 1), clamped.
double rotation_angle_rad(const Mat3& R) { return std::acos(std::clamp(0.5 * (R.trace() - 1.0), -1.0, 1.0)); }

}  // namespace

KittiMetric compute_kitti_metric(const Trajectory& gt, const Trajectory& est) {
  if (gt.size() != est.size()) throw std::invalid_argument("KITTI metric needs matched trajectories");
  const std::vector<double> dist = accumulated_distances(gt);
  double t_sum = 0, r_sum = 0;
  KittiMetric m;
  for (std::size_t first = 0; first < gt.size(); first += kStepFrames) {
    for (double length : kLengthsM) {
      // First frame strictly farther than `length` along the ground-truth path (devkit lastFrameFromSegmentLength).
      const auto it = std::upper_bound(dist.begin() + first, dist.end(), dist[first] + length);
      if (it == dist.end()) continue;
      const std::size_t last = static_cast<std::size_t>(it - dist.begin());
      const SE3 gt_delta = gt[first].T_W_B.inverse() * gt[last].T_W_B;
      const SE3 est_delta = est[first].T_W_B.inverse() * est[last].T_W_B;
      const SE3 error = est_delta.inverse() * gt_delta;
      t_sum += error.translation().norm() / length;
      r_sum += rotation_angle_rad(error.rotation()) / length;
      ++m.segments;
    }
  }
  if (m.segments > 0) {
    m.t_err_percent = 100.0 * t_sum / static_cast<double>(m.segments);
    m.r_err_deg_per_m = r_sum / static_cast<double>(m.segments) * 180.0 / M_PI;
  }
  return m;
}

}  // namespace vilslam::eval
