#pragma once
// Pinhole camera with radial-tangential or equidistant (Kannala-Brandt) distortion, as in Kalibr/EuRoC.
// Normalized coordinates are undistorted (x/z, y/z) in the camera frame C.
#include <Eigen/Core>

#include "common/calibration.h"

namespace vilslam {

class CameraModel {
 public:
  // Throws InputError("camera", ...) when the distortion coefficients do not fit the model.
  explicit CameraModel(const CameraIntrinsics& intrinsics);

  const CameraIntrinsics& intrinsics() const { return intrinsics_; }

  // Undistorted normalized coordinates -> distorted normalized coordinates; J_distort = d(out)/d(xy).
  Eigen::Vector2d distort(const Eigen::Vector2d& xy, Eigen::Matrix2d* J_distort = nullptr) const;
  // Inverse of distort (Gauss-Newton on the analytic Jacobian; Newton on theta for equidistant). An
  // equidistant pixel more than 90 degrees off the optical axis has no normalized coordinates.
  Eigen::Vector2d undistort(const Eigen::Vector2d& xy_distorted) const;

  // Undistorted normalized coordinates -> distorted pixel; J_px = d(px)/d(xy).
  Eigen::Vector2d normalized_to_pixel(const Eigen::Vector2d& xy, Eigen::Matrix2d* J_px = nullptr) const;
  // Distorted pixel -> undistorted normalized coordinates.
  Eigen::Vector2d pixel_to_normalized(const Eigen::Vector2d& px) const;

  // Point p_C in the camera frame -> distorted pixel; false when z <= min_depth_m. J_px_p = d(px)/d(p_C).
  bool project(const Eigen::Vector3d& p_C, Eigen::Vector2d* px,
               Eigen::Matrix<double, 2, 3>* J_px_p = nullptr, double min_depth_m = 1e-6) const;
  // Distorted pixel -> bearing (x, y, 1) in C.
  Eigen::Vector3d unproject(const Eigen::Vector2d& px) const;

  bool in_image(const Eigen::Vector2d& px, double border_px = 0) const;

  // Average focal length, to turn normalized-plane distances into pixels.
  double focal_px() const { return 0.5 * (intrinsics_.fx + intrinsics_.fy); }

 private:
  CameraIntrinsics intrinsics_;
};

}  // namespace vilslam

namespace vilslam {

// The calibrated stereo pair: left camera C0, right camera C1 and T_C1_C0 (points from C0 into C1).
struct StereoRig {
  CameraModel cam0;
  CameraModel cam1;
  SE3 T_C1_C0;
};

StereoRig make_stereo_rig(const RigCalibration& calib);

}  // namespace vilslam
