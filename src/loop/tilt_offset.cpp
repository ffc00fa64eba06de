#include "loop/tilt_offset.h"

namespace vilslam::loop {

namespace {

// epsilon_L's prior, as a share of the samples' total weight; epsilon_W's, only to keep the system regular
// (the directions about up are never seen).
constexpr double kMountPriorShare = 0.1;
constexpr double kMapPriorShare = 1e-6;

}  // namespace

void UpOffsetSamples::add(const Vec3& up_L_measured, const Mat3& R_W_L, double sample_weight) {
  const Vec3 u = up_L_measured.normalized();
  const Vec3 v = R_W_L.transpose() * Vec3::UnitZ();
  const Mat3 P = Mat3::Identity() - u * u.transpose();
  Eigen::Matrix<double, 3, 6> H;
  H << P, P * R_W_L.transpose();
  // u x v turns u towards v by the angle between them (its sine; the angles are fractions of a degree).
  normal += sample_weight * H.transpose() * H;
  rhs += sample_weight * H.transpose() * u.cross(v);
  weight += sample_weight;
}

void UpOffsetSamples::rotate_world(const Mat3& R_new_old) {
  // epsilon_W_old = R_new_old^T epsilon_W_new: substitute x_old = M x_new.
  Eigen::Matrix<double, 6, 6> M = Eigen::Matrix<double, 6, 6>::Identity();
  M.bottomRightCorner<3, 3>() = R_new_old.transpose();
  normal = M.transpose() * normal * M;
  rhs = M.transpose() * rhs;
}

Vec3 UpOffsetSamples::mount() const {
  if (weight <= 0.0) return Vec3::Zero();
  Eigen::Matrix<double, 6, 6> A = normal;
  A.diagonal().head<3>().array() += kMountPriorShare * weight;
  A.diagonal().tail<3>().array() += kMapPriorShare * weight;
  return A.ldlt().solve(rhs).head<3>();
}

}  // namespace vilslam::loop
