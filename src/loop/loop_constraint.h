#pragma once
// The two estimates of a loop constraint (paper, "Loop constraint"): EPnP in RANSAC on the candidate's
// stereo-triangulated points, then ICP of the query key scan's sparse features against the candidate's.
#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "common/lie.h"
#include "lidar/feature_map.h"

namespace vilslam::loop {

struct PnpSettings {
  int ransac_iterations = 200;
  double reprojection_px = 3.0;
  double focal_px = 1.0;  // turns the pixel threshold into normalized coordinates
  std::uint64_t seed = 1;
};

struct PnpEstimate {
  bool valid = false;
  SE3 T_C0v_C0u;  // maps points of the candidate's left camera into the query's
  int inliers = 0;
};

// EPnP (Lepetit et al. 2009) inside RANSAC (cv::solvePnPRansac, SOLVEPNP_EPNP, at most ransac_iterations,
// cv::theRNG() seeded), then Levenberg-Marquardt on the inliers' reprojection error. p_C0u[i] is seen at
// the undistorted normalized coordinates xy_C0v[i]. Invalid with fewer than 5 points or when RANSAC fails.
PnpEstimate estimate_pnp(const std::vector<Vec3>& p_C0u, const std::vector<Eigen::Vector2d>& xy_C0v,
                         const PnpSettings& settings);

// The camera constraint moved into the key scans' frames: T_Lu_Lv = T_Lu_C0u * T_C0u_C0v * T_Lv_C0v^-1.
SE3 lidar_constraint_from_camera(const SE3& T_C0v_C0u, const SE3& T_Lu_C0u, const SE3& T_Lv_C0v);

// Translation (m) and rotation angle (rad) of a^-1 b.
struct PoseDifference {
  double translation_m = 0.0;
  double rotation_rad = 0.0;
};
PoseDifference pose_difference(const SE3& a, const SE3& b);

}  // namespace vilslam::loop
