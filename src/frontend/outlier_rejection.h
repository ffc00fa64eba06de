#pragma once
// Geometric checks of stereo matches: triangulation, stereo and temporal reprojection errors, and the
// frame-to-frame motion that the temporal check needs.
#include <Eigen/Core>
#include <vector>

#include "common/lie.h"
#include "frontend/camera_model.h"
#include "frontend/frontend_config.h"

namespace vilslam {

// Linear (DLT) triangulation of the normalized observations xy0 in C0 and xy1 in C1. Returns false when
// the point is not in front of both cameras.
bool triangulate_stereo(const Eigen::Vector2d& xy0, const Eigen::Vector2d& xy1, const SE3& T_C1_C0, Vec3* p_C0);

// Average of the left and right pixel reprojection errors of p_C0 against the measured distorted
// pixels; +infinity when the point is behind a camera.
double stereo_reprojection_error_px(const StereoRig& rig, const Vec3& p_C0, const Eigen::Vector2d& left_px,
                                    const Eigen::Vector2d& right_px);

struct MotionEstimate {
  bool valid = false;
  SE3 T_C0cur_C0prev;  // maps points of the previous left camera frame into the current one
  int inliers = 0;
};

// The minimal solver inside RANSAC: P3P for frame-to-frame tracking, EPnP (Lepetit et al. 2009) for the
// loop constraint (paper, "Loop constraint").
enum class PnpSolver { kP3P, kEPnP };

// Frame-to-frame motion of the left camera from 3D points of the previous pair (p_C0prev) and their
// normalized observations in the current left image: RANSAC of the solver (cv::solvePnPRansac, at most
// config.pnp_ransac_iterations, seeded through cv::theRNG with config.ransac_seed) and Levenberg-Marquardt
// refinement on the inliers. Invalid when fewer than config.pnp_min_points points or inliers.
MotionEstimate estimate_motion_pnp(const std::vector<Vec3>& p_C0prev, const std::vector<Eigen::Vector2d>& xy_cur,
                                   double focal_px, const FrontendConfig& config, PnpSolver solver = PnpSolver::kP3P);

}  // namespace vilslam
