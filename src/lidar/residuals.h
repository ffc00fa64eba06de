#pragma once
// LOAM residuals of scan-to-map registration with analytic Jacobians. The pose is perturbed on the right,
// T_W_L Exp(delta) with delta = [rho; phi] in the LiDAR frame (common/lie.h ordering), so that
// d(T Exp(delta) p)/d delta at 0 = [R, -R [p]x].
#include <Eigen/Core>

#include "common/lie.h"

namespace vilslam::lidar {

// A feature point p_L and the map line through point_W along the unit vector direction_W.
struct EdgeCorrespondence {
  Vec3 p_L = Vec3::Zero();
  Vec3 point_W = Vec3::Zero();
  Vec3 direction_W = Vec3::UnitX();
};

// A feature point p_L and the map plane {x : normal_W . x + offset_m = 0} (unit normal).
struct PlaneCorrespondence {
  Vec3 p_L = Vec3::Zero();
  Vec3 normal_W = Vec3::UnitZ();
  double offset_m = 0.0;
};

using Jacobian3x6 = Eigen::Matrix<double, 3, 6>;
using Jacobian1x6 = Eigen::Matrix<double, 1, 6>;

// u x (T p - c): its norm is the point-to-line distance (paper r_E).
Vec3 edge_residual(const SE3& T_W_L, const EdgeCorrespondence& c, Jacobian3x6* J = nullptr);
// n . (T p) + d: the signed point-to-plane distance (paper r_U).
double plane_residual(const SE3& T_W_L, const PlaneCorrespondence& c, Jacobian1x6* J = nullptr);
// Tilt prior: R_W_L^T e_z - up_L_prior, the world's up seen in L against a gravity-referenced prior's (VIO).
// Its Jacobian is [v]x on phi (v = R_W_L^T e_z) and 0 on rho; it does not see yaw (rotation about v).
Vec3 tilt_residual(const SE3& T_W_L, const Vec3& up_L_prior, Jacobian3x6* J = nullptr);

}  // namespace vilslam::lidar
