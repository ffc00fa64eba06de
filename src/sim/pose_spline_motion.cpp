#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "sim/trajectory.h"

namespace vilslam::sim {
namespace {

// Knot spacing that divides the span into whole segments, about config.knot_spacing_s each.
int segment_count(const Trajectory& poses, const PoseSplineConfig& config) {
  if (poses.size() < 2 || poses.back().t_ns <= poses.front().t_ns)
    throw std::invalid_argument("pose spline needs at least 2 poses spanning some time");
  if (!(config.knot_spacing_s > 0)) throw std::invalid_argument("pose spline: knot spacing must be positive");
  const double span_s = ns_to_s(poses.back().t_ns - poses.front().t_ns);
  return std::max(1, static_cast<int>(std::ceil(span_s / config.knot_spacing_s)));
}

// Columns [p; q_wxyz] with quaternion signs made continuous (q and -q are the same rotation).
UniformBSpline fit_poses(const Trajectory& poses, const PoseSplineConfig& config) {
  const int segments = segment_count(poses, config);
  const double span_ns = static_cast<double>(poses.back().t_ns - poses.front().t_ns);
  std::vector<double> u(poses.size());
  Eigen::MatrixXd values(7, poses.size());
  Eigen::Vector4d previous(1, 0, 0, 0);
  for (std::size_t j = 0; j < poses.size(); ++j) {
    const Quat& q = poses[j].T_W_B.quat();
    Eigen::Vector4d q_wxyz(q.w(), q.x(), q.y(), q.z());
    if (j > 0 && q_wxyz.dot(previous) < 0) q_wxyz = -q_wxyz;
    previous = q_wxyz;
    u[j] = static_cast<double>(poses[j].t_ns - poses.front().t_ns) / span_ns * segments;
    values.col(static_cast<Eigen::Index>(j)) << poses[j].T_W_B.translation(), q_wxyz;
  }
  return UniformBSpline::fit(u, values, segments + 3, config.smoothing);
}

}  // namespace

PoseSplineMotion::PoseSplineMotion(const Trajectory& poses, const PoseSplineConfig& config)
    : spline_(fit_poses(poses, config)) {
  start_ns_ = poses.front().t_ns;
  end_ns_ = poses.back().t_ns;
  knot_spacing_s_ = ns_to_s(end_ns_ - start_ns_) / spline_.max_u();
}

MotionState PoseSplineMotion::state(TimeNs t_ns) const {
  t_ns = std::clamp(t_ns, start_ns_, end_ns_);
  const SplinePoint s = spline_.eval(ns_to_s(t_ns - start_ns_) / knot_spacing_s_);
  const double dt = knot_spacing_s_;
  MotionState out;
  out.t_ns = t_ns;
  out.v_W = s.d1.head<3>() / dt;
  out.a_W = s.d2.head<3>() / (dt * dt);
  // Normalized quaternion q = p / |p| and its rate q' = (p' - q (q.p')) / |p|.
  const Eigen::Vector4d p = s.value.tail<4>(), p_dot = s.d1.tail<4>() / dt;
  const Eigen::Vector4d q = p / p.norm();
  const Eigen::Vector4d q_dot = (p_dot - q * q.dot(p_dot)) / p.norm();
  const Quat q_W_I(q[0], q[1], q[2], q[3]);
  // Body rate: omega_I = 2 vec(q^* (x) q_dot) (Sola, "Quaternion kinematics", eq. 108).
  const Quat rate = q_W_I.conjugate() * Quat(q_dot[0], q_dot[1], q_dot[2], q_dot[3]);
  out.omega_I = 2.0 * rate.vec();
  out.T_W_I = SE3(q_W_I, Vec3(s.value.head<3>()));
  return out;
}

}  // namespace vilslam::sim
