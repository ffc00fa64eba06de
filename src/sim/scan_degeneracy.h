#pragma once
// How well one LiDAR sweep constrains the 6-DoF pose: the point-to-plane information matrix
// sum J^T J with J = [n^T, (p x n)^T] over the sweep's points (true normals), and its eigen-analysis
// (Zhang, Kaess, Singh, "On degeneracy of optimization-based state estimation problems", ICRA 2016).
#include "common/lie.h"
#include "sim/lidar_sim.h"
#include "sim/world.h"

namespace vilslam::sim {

struct ScanDegeneracy {
  int num_points = 0;
  Mat6 information = Mat6::Zero();  // order [translation; rotation], axes of W, about the sensor
  Vec6 eigenvalues = Vec6::Zero();  // ascending
  Mat6 eigenvectors = Mat6::Zero(); // columns, matching eigenvalues
  double min_max_ratio = 0;         // smallest / largest eigenvalue
  Vec6 weakest_direction = Vec6::Zero();  // unit eigenvector of the smallest eigenvalue
};

// Casts one static, noise-free sweep at T_W_L. p is each return relative to the sensor in W's axes,
// n its surface normal, so a small motion [dt; dphi] changes the point-to-plane residual by J [dt; dphi].
ScanDegeneracy analyze_scan_degeneracy(const World& world, const LidarSimConfig& config, const SE3& T_W_L);

}  // namespace vilslam::sim
