#pragma once
// Rigid ICP of a point set (a SLAM map) onto a reference model held in a k-d tree.
//   point-to-point: each iteration solves the matched pairs in closed form (Umeyama, se3);
//   point-to-plane: each iteration solves the linearized normal equations of
//                   sum (n_q . (R p + t - q))^2 (Chen & Medioni 1992) for a small rotation and translation.
// Correspondences farther than max_correspondence_m are ignored.
#include <Eigen/Core>
#include <cstddef>
#include <vector>

#include "common/lie.h"
#include "common/point_index.h"

namespace vilslam::eval {

enum class IcpMode { kPointToPoint, kPointToPlane };

struct IcpConfig {
  IcpMode mode = IcpMode::kPointToPlane;
  int max_iterations = 50;
  double max_correspondence_m = 1.0;
  double convergence_m = 1e-6;  // stop when an update moves points by less than this
  std::size_t normal_neighbours = 10;
  // Point-to-plane: a direction of the normal equations whose eigenvalue is below this times the number of
  // correspondences is unconstrained (a tunnel's axis, where every normal is across it) and the update
  // leaves the alignment unchanged along it, instead of sliding the map along the tunnel.
  double min_eigenvalue_per_match = 1e-3;
};

struct IcpResult {
  SE3 T_model_map;  // p_model = T_model_map * p_map
  int iterations = 0;
  bool converged = false;
  std::size_t inliers = 0;  // correspondences used in the last iteration
  double rmse_m = 0;        // of those correspondences, before the last update
  int degenerate_directions = 0;  // point-to-plane: unconstrained directions in the last iteration
};

// Unit normals of the model points from their k nearest neighbours (smallest-eigenvalue direction).
std::vector<Eigen::Vector3f> estimate_normals(const PointIndex& model, std::size_t neighbours);

// Normals are used only for point-to-plane (pass the estimate_normals result, or empty for point-to-point).
// Throws std::invalid_argument when too few correspondences remain to solve for a pose.
IcpResult align_icp(const std::vector<Eigen::Vector3f>& map, const PointIndex& model,
                    const std::vector<Eigen::Vector3f>& model_normals, const IcpConfig& config,
                    const SE3& T_model_map_initial = SE3());

}  // namespace vilslam::eval
