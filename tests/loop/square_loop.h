#pragma once
// A synthetic closed loop for the pose-graph tests: a 10 m square driven a little more than once, with
// odometry from the true relative motion plus a constant bias, and loop constraints from the truth.
#include <cmath>
#include <cstddef>
#include <vector>

#include "common/lie.h"
#include "common/types.h"
#include "loop/pose_graph.h"

namespace vilslam::test {

struct SquareLoop {
  Trajectory truth;
  Trajectory drifted;  // integrated biased odometry, starting at the true first pose
  std::size_t lap_poses = 0;  // pose lap_poses + k is at the place of pose k
  std::vector<loop::RelativePoseConstraint> odometry;
};

constexpr double kOdometrySigmaM = 0.02;
constexpr double kOdometrySigmaRad = 0.002;
constexpr double kLoopSigmaM = 0.01;
constexpr double kLoopSigmaRad = 0.001;

// Steps of 0.5 m along the sides of a 10 m square (20 per side), turning 90 degrees at the corners,
// with a gentle height and roll wave so that every axis is excited; extra_poses go on past the start.
inline SquareLoop make_square_loop(std::size_t extra_poses = 12) {
  constexpr std::size_t kPerSide = 20;
  constexpr double kStepM = 0.5;
  SquareLoop s;
  s.lap_poses = 4 * kPerSide;
  for (std::size_t i = 0; i <= s.lap_poses + extra_poses; ++i) {
    const std::size_t k = i % s.lap_poses;
    const std::size_t side = k / kPerSide;
    const double along = kStepM * static_cast<double>(k % kPerSide);
    const double yaw = M_PI / 2.0 * static_cast<double>(side);
    const Vec3 corners[4] = {{0, 0, 0}, {10, 0, 0}, {10, 10, 0}, {0, 10, 0}};
    const double wave = std::sin(2.0 * M_PI * static_cast<double>(k) / static_cast<double>(s.lap_poses));
    const Vec3 p = corners[side] + along * Vec3(std::cos(yaw), std::sin(yaw), 0.0) + Vec3(0, 0, 0.3 * wave);
    const Quat q = Quat(Eigen::AngleAxisd(yaw, Vec3::UnitZ())) * Quat(Eigen::AngleAxisd(0.05 * wave, Vec3::UnitX()));
    s.truth.push_back({static_cast<TimeNs>(i) * 100'000'000, SE3(q, p)});
  }
  Vec6 bias;
  bias << 0.004, 0.002, 0.001, 0.0005, 0.0003, 0.003;
  const SE3 T_bias = SE3::exp(bias);
  const loop::RelativePoseConstraint template_constraint{
      0, 0, SE3(), loop::information_from_sigmas(kOdometrySigmaM, kOdometrySigmaRad), loop::ConstraintKind::kOdometry};
  s.drifted.push_back(s.truth.front());
  for (std::size_t i = 1; i < s.truth.size(); ++i) {
    loop::RelativePoseConstraint c = template_constraint;
    c.from_index = i - 1;
    c.to_index = i;
    c.T_from_to = s.truth[i - 1].T_W_B.inverse() * s.truth[i].T_W_B * T_bias;
    s.odometry.push_back(c);
    s.drifted.push_back({s.truth[i].t_ns, s.drifted.back().T_W_B * c.T_from_to});
  }
  return s;
}

// A loop constraint from u to v measured from the truth.
inline loop::RelativePoseConstraint true_loop(const SquareLoop& s, std::size_t u, std::size_t v) {
  return {u, v, s.truth[u].T_W_B.inverse() * s.truth[v].T_W_B,
          loop::information_from_sigmas(kLoopSigmaM, kLoopSigmaRad), loop::ConstraintKind::kLoop};
}

// RMS of the position errors against the truth (no alignment: the first pose is the fixed gauge).
inline double position_rmse(const Trajectory& est, const Trajectory& truth) {
  double sum_sq = 0.0;
  for (std::size_t i = 0; i < est.size(); ++i) {
    sum_sq += (est[i].T_W_B.translation() - truth[i].T_W_B.translation()).squaredNorm();
  }
  return std::sqrt(sum_sq / static_cast<double>(est.size()));
}

// Distance between pose lap_poses and pose 0, which coincide in the truth.
inline double end_to_start_m(const SquareLoop& s, const Trajectory& est) {
  return (est[s.lap_poses].T_W_B.translation() - est[0].T_W_B.translation()).norm();
}

inline loop::PoseGraph graph_of(const SquareLoop& s, const std::vector<loop::RelativePoseConstraint>& loops) {
  loop::PoseGraph graph;
  for (const TimedPose& p : s.drifted) graph.add_pose(p.t_ns, p.T_W_B);
  for (const auto& c : s.odometry) graph.add_constraint(c);
  for (const auto& c : loops) graph.add_constraint(c);
  return graph;
}

}  // namespace vilslam::test
