#include "frontend/camera_model.h"

#include <cmath>

#include "common/error.h"

namespace vilslam {
namespace {

constexpr int kMaxUndistortIterations = 20;
constexpr double kUndistortTolerance = 1e-15;

// Radial-tangential (Brown-Conrady, OpenCV order k1 k2 p1 p2):
// x_d = x (1 + k1 r^2 + k2 r^4) + 2 p1 x y + p2 (r^2 + 2 x^2), y_d likewise with p1 and p2 swapped.
Eigen::Vector2d distort_radtan(const std::vector<double>& k, const Eigen::Vector2d& xy, Eigen::Matrix2d* J) {
  const double x = xy.x(), y = xy.y(), p1 = k[2], p2 = k[3];
  const double r2 = x * x + y * y;
  const double radial = 1 + k[0] * r2 + k[1] * r2 * r2;
  if (J) {
    const double dradial_dr2 = k[0] + 2 * k[1] * r2;
    (*J)(0, 0) = radial + 2 * x * x * dradial_dr2 + 2 * p1 * y + 6 * p2 * x;
    (*J)(0, 1) = 2 * x * y * dradial_dr2 + 2 * p1 * x + 2 * p2 * y;
    (*J)(1, 0) = (*J)(0, 1);
    (*J)(1, 1) = radial + 2 * y * y * dradial_dr2 + 6 * p1 * y + 2 * p2 * x;
  }
  return {x * radial + 2 * p1 * x * y + p2 * (r2 + 2 * x * x), y * radial + p1 * (r2 + 2 * y * y) + 2 * p2 * x * y};
}

// theta_d = theta (1 + k1 theta^2 + k2 theta^4 + k3 theta^6 + k4 theta^8) and its derivative.
double equidistant_theta_d(const std::vector<double>& k, double theta, double* dtheta_d) {
  const double t2 = theta * theta;
  const double poly = 1 + t2 * (k[0] + t2 * (k[1] + t2 * (k[2] + t2 * k[3])));
  if (dtheta_d) *dtheta_d = 1 + t2 * (3 * k[0] + t2 * (5 * k[1] + t2 * (7 * k[2] + t2 * 9 * k[3])));
  return theta * poly;
}

// Equidistant (Kannala-Brandt, Kalibr "equidistant", OpenCV fisheye): x_d = (theta_d / r) x, theta = atan(r).
Eigen::Vector2d distort_equidistant(const std::vector<double>& k, const Eigen::Vector2d& xy, Eigen::Matrix2d* J) {
  const double r = xy.norm();
  if (r < 1e-10) {
    if (J) J->setIdentity();
    return xy;
  }
  const double theta = std::atan(r);
  double dtheta_d = 0;
  const double s = equidistant_theta_d(k, theta, &dtheta_d) / r;
  if (J) {
    // d/dxy of s(r) xy = s I + (s'(r) / r) xy xy^T, with s'(r) = (theta_d'(theta) / (1 + r^2) - s) / r.
    const double ds_dr = (dtheta_d / (1 + r * r) - s) / r;
    *J = s * Eigen::Matrix2d::Identity() + (ds_dr / r) * xy * xy.transpose();
  }
  return s * xy;
}

Eigen::Vector2d undistort_equidistant(const std::vector<double>& k, const Eigen::Vector2d& xy_d) {
  const double theta_d = xy_d.norm();
  if (theta_d < 1e-10) return xy_d;
  double theta = theta_d;
  for (int i = 0; i < kMaxUndistortIterations; ++i) {
    double dtheta_d = 0;
    const double step = (equidistant_theta_d(k, theta, &dtheta_d) - theta_d) / dtheta_d;
    theta -= step;
    if (std::abs(step) < kUndistortTolerance) break;
  }
  return xy_d * (std::tan(theta) / theta_d);
}

}  // namespace

CameraModel::CameraModel(const CameraIntrinsics& intrinsics) : intrinsics_(intrinsics) {
  const std::size_t expected = intrinsics.distortion == DistortionModel::kNone ? 0 : 4;
  if (intrinsics.distortion_coeffs.size() != expected) {
    throw InputError("camera", "expected " + std::to_string(expected) + " distortion coefficients, got " +
                                   std::to_string(intrinsics.distortion_coeffs.size()));
  }
  if (!(intrinsics.fx > 0 && intrinsics.fy > 0)) throw InputError("camera", "focal lengths must be positive");
}

Eigen::Vector2d CameraModel::distort(const Eigen::Vector2d& xy, Eigen::Matrix2d* J_distort) const {
  switch (intrinsics_.distortion) {
    case DistortionModel::kRadTan:
      return distort_radtan(intrinsics_.distortion_coeffs, xy, J_distort);
    case DistortionModel::kEquidistant:
      return distort_equidistant(intrinsics_.distortion_coeffs, xy, J_distort);
    case DistortionModel::kNone:
      break;
  }
  if (J_distort) J_distort->setIdentity();
  return xy;
}

Eigen::Vector2d CameraModel::undistort(const Eigen::Vector2d& xy_distorted) const {
  switch (intrinsics_.distortion) {
    case DistortionModel::kEquidistant:
      return undistort_equidistant(intrinsics_.distortion_coeffs, xy_distorted);
    case DistortionModel::kRadTan: {
      Eigen::Vector2d xy = xy_distorted;
      for (int i = 0; i < kMaxUndistortIterations; ++i) {
        Eigen::Matrix2d J;
        const Eigen::Vector2d residual = distort(xy, &J) - xy_distorted;
        const Eigen::Vector2d step = J.inverse() * residual;
        xy -= step;
        if (step.squaredNorm() < kUndistortTolerance * kUndistortTolerance) break;
      }
      return xy;
    }
    case DistortionModel::kNone:
      break;
  }
  return xy_distorted;
}

Eigen::Vector2d CameraModel::normalized_to_pixel(const Eigen::Vector2d& xy, Eigen::Matrix2d* J_px) const {
  const Eigen::Vector2d d = distort(xy, J_px);
  if (J_px) {
    J_px->row(0) *= intrinsics_.fx;
    J_px->row(1) *= intrinsics_.fy;
  }
  return {intrinsics_.fx * d.x() + intrinsics_.cx, intrinsics_.fy * d.y() + intrinsics_.cy};
}

Eigen::Vector2d CameraModel::pixel_to_normalized(const Eigen::Vector2d& px) const {
  return undistort({(px.x() - intrinsics_.cx) / intrinsics_.fx, (px.y() - intrinsics_.cy) / intrinsics_.fy});
}

bool CameraModel::project(const Eigen::Vector3d& p_C, Eigen::Vector2d* px, Eigen::Matrix<double, 2, 3>* J_px_p,
                          double min_depth_m) const {
  if (!(p_C.z() > min_depth_m)) return false;
  const double inv_z = 1.0 / p_C.z();
  const Eigen::Vector2d xy(p_C.x() * inv_z, p_C.y() * inv_z);
  Eigen::Matrix2d J_px_xy;
  *px = normalized_to_pixel(xy, J_px_p ? &J_px_xy : nullptr);
  if (J_px_p) {
    Eigen::Matrix<double, 2, 3> J_xy_p;
    J_xy_p << inv_z, 0, -xy.x() * inv_z, 0, inv_z, -xy.y() * inv_z;
    *J_px_p = J_px_xy * J_xy_p;
  }
  return true;
}

Eigen::Vector3d CameraModel::unproject(const Eigen::Vector2d& px) const {
  return pixel_to_normalized(px).homogeneous();
}

bool CameraModel::in_image(const Eigen::Vector2d& px, double border_px) const {
  return px.x() >= border_px && px.y() >= border_px && px.x() <= intrinsics_.width_px - 1 - border_px &&
         px.y() <= intrinsics_.height_px - 1 - border_px;
}

}  // namespace vilslam

namespace vilslam {

StereoRig make_stereo_rig(const RigCalibration& calib) {
  return {CameraModel(calib.cam0), CameraModel(calib.cam1), calib.T_C0_C1().inverse()};
}

}  // namespace vilslam
