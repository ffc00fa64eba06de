#pragma once
// Fusion of the two loop constraint estimates by their information (beyond the paper, which keeps ICP's
// result): EPnP's information from the reprojection Jacobians of its inliers, ICP's from its J^T J. Along a
// direction the scans barely constrain (a tunnel's roll, a corridor's axis) the visual estimate then wins,
// elsewhere the LiDAR's (docs/loop.md, "Fusing EPnP and ICP").
#include <vector>

#include "common/lie.h"

namespace vilslam::loop {

// Information of T_C0cur_C0prev for a right perturbation [rho; phi]: sum over the inliers (reprojection within
// inlier_px) of J^T J / sigma_px^2, J the pixel reprojection Jacobian of p_C0prev into the current camera.
// xy_cur: normalized image coordinates of the current camera; focal_px turns them into pixels.
Mat6 pnp_information(const SE3& T_C0cur_C0prev, const std::vector<Vec3>& p_C0prev,
                     const std::vector<Eigen::Vector2d>& xy_cur, double focal_px, double inlier_px, double sigma_px);

// The information of T_C0v_C0u carried to T_Lu_Lv = T_Lu_C0u T_C0v_C0u^-1 T_C0v_Lv (right perturbations).
Mat6 information_in_lidar_frames(const Mat6& information_C0v_C0u, const SE3& T_C0v_C0u, const SE3& T_Lv_C0v);

// The minimum of |Log(T_a^-1 T)|^2_{info_a} + |Log(T_b^-1 T)|^2_{info_b}, linearized at T_b:
// T = T_b Exp((info_a + info_b)^-1 info_a Log(T_b^-1 T_a)).
SE3 fuse_estimates(const SE3& T_a, const Mat6& info_a, const SE3& T_b, const Mat6& info_b);

// (estimate_information^-1 + floor_information^-1)^-1: the covariances added, so every direction is at most as
// certain as the floor says and no more certain than the estimate. A direction the estimate does not measure
// (zero information) gets none. floor_information must be positive definite.
Mat6 information_with_floor(const Mat6& estimate_information, const Mat6& floor_information);

}  // namespace vilslam::loop
