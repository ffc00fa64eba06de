#pragma once
// A long synthetic drive for the global pose graph: laps around a 50 m x 75 m block (500 LiDAR poses of 0.5 m
// a lap, 10 Hz) with a height and roll wave, LiDAR odometry with a bias and white noise (about 1 % drift), and
// one loop a lap to the same place on the previous lap, at a random place along the lap. Deterministic.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <random>
#include <vector>

#include "common/lie.h"
#include "common/types.h"
#include "loop/pose_graph.h"

namespace vilslam::test {

struct BlockRoute {
  Trajectory truth;
  std::vector<SE3> odometry;  // odometry[i] = measured T_{i-1,i}; odometry[0] = identity
  std::size_t lap_poses = 500;
  std::vector<loop::RelativePoseConstraint> loops;  // sorted by to_index (the newer pose), to_index < pose_count
};

constexpr double kRouteOdometrySigmaM = 0.005;
constexpr double kRouteOdometrySigmaRad = 0.0003;
constexpr double kRouteLoopSigmaM = 0.02;
constexpr double kRouteLoopSigmaRad = 0.002;

// Pose k of a lap: straight sides, a 90 degree turn over the last 10 poses of each side.
inline SE3 block_pose(std::size_t k, std::size_t lap_poses) {
  constexpr double kStepM = 0.5;
  const double s = kStepM * static_cast<double>(k % lap_poses);  // path length along the lap
  const double sides[4] = {75.0, 50.0, 75.0, 50.0};
  const Vec3 corners[4] = {{0, 0, 0}, {75, 0, 0}, {75, 50, 0}, {0, 50, 0}};
  double along = s;
  int side = 0;
  while (side < 3 && along >= sides[side]) along -= sides[side++];
  const double turn = std::clamp((along - (sides[side] - 5.0)) / 5.0, 0.0, 1.0);
  const double yaw = M_PI / 2.0 * (side + turn);
  const double base_yaw = M_PI / 2.0 * side;
  const double phase = 2.0 * M_PI * s / 250.0;
  const Vec3 p = corners[side] + along * Vec3(std::cos(base_yaw), std::sin(base_yaw), 0.0) +
                 Vec3(0, 0, 0.5 * std::sin(3.0 * phase));
  const Quat q = Quat(Eigen::AngleAxisd(yaw, Vec3::UnitZ())) * Quat(Eigen::AngleAxisd(0.03 * std::sin(phase), Vec3::UnitX()));
  return SE3(q, p);
}

inline BlockRoute make_block_route(std::size_t pose_count, unsigned seed = 1) {
  BlockRoute r;
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  auto noise = [&](double sigma_m, double sigma_rad) {
    Vec6 xi;
    for (int i = 0; i < 6; ++i) xi[i] = normal(rng) * (i < 3 ? sigma_m : sigma_rad);
    return xi;
  };
  Vec6 bias;
  bias << 0.002, 0.001, 0.0005, 0.00005, 0.00005, 0.0001;
  r.odometry.push_back(SE3());
  for (std::size_t i = 0; i < pose_count; ++i) {
    r.truth.push_back({static_cast<TimeNs>(i) * 100'000'000, block_pose(i, r.lap_poses)});
    if (i == 0) continue;
    const SE3 T_true = r.truth[i - 1].T_W_B.inverse() * r.truth[i].T_W_B;
    r.odometry.push_back(T_true * SE3::exp(bias + noise(kRouteOdometrySigmaM, kRouteOdometrySigmaRad)));
  }
  std::uniform_int_distribution<std::size_t> place(0, r.lap_poses - 1);
  const Mat6 loop_information = loop::information_from_sigmas(kRouteLoopSigmaM, kRouteLoopSigmaRad);
  for (std::size_t lap = 1;; ++lap) {
    const std::size_t v = lap * r.lap_poses + place(rng);
    if (v >= pose_count) break;
    const std::size_t u = v - r.lap_poses;
    const SE3 T_u_v = r.truth[u].T_W_B.inverse() * r.truth[v].T_W_B * SE3::exp(noise(kRouteLoopSigmaM, kRouteLoopSigmaRad));
    r.loops.push_back({u, v, T_u_v, loop_information, loop::ConstraintKind::kLoop});
  }
  return r;
}

// The drifted trajectory: the odometry integrated from the true first pose.
inline Trajectory dead_reckoning(const BlockRoute& r) {
  Trajectory poses = {r.truth.front()};
  for (std::size_t i = 1; i < r.truth.size(); ++i) {
    poses.push_back({r.truth[i].t_ns, poses.back().T_W_B * r.odometry[i]});
  }
  return poses;
}

}  // namespace vilslam::test
