#include "lidar/residuals.h"

namespace vilslam::lidar {

namespace {

// d(T Exp(delta) p)/d delta at delta = 0.
Jacobian3x6 point_jacobian(const SE3& T_W_L, const Vec3& p_L) {
  Jacobian3x6 J;
  const Mat3 R = T_W_L.rotation();
  J.leftCols<3>() = R;
  J.rightCols<3>() = -R * so3::hat(p_L);
  return J;
}

}  // namespace

Vec3 edge_residual(const SE3& T_W_L, const EdgeCorrespondence& c, Jacobian3x6* J) {
  const Mat3 u_hat = so3::hat(c.direction_W);
  if (J) *J = u_hat * point_jacobian(T_W_L, c.p_L);
  return u_hat * (T_W_L * c.p_L - c.point_W);
}

double plane_residual(const SE3& T_W_L, const PlaneCorrespondence& c, Jacobian1x6* J) {
  if (J) *J = c.normal_W.transpose() * point_jacobian(T_W_L, c.p_L);
  return c.normal_W.dot(T_W_L * c.p_L) + c.offset_m;
}

Vec3 tilt_residual(const SE3& T_W_L, const Vec3& up_L_prior, Jacobian3x6* J) {
  const Vec3 up_L = T_W_L.rotation().transpose() * Vec3::UnitZ();
  // (R Exp(phi))^T e_z = Exp(-phi) v ~ v - phi x v = v + [v]x phi.
  if (J) *J << Mat3::Zero(), so3::hat(up_L);
  return up_L - up_L_prior;
}

}  // namespace vilslam::lidar
