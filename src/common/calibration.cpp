#include "common/calibration.h"

#include <cmath>

#include "common/error.h"

namespace vilslam {
namespace {

void validate_camera(const CameraIntrinsics& cam, const std::string& name, const std::string& source) {
  if (cam.width_px <= 0 || cam.height_px <= 0) throw InputError(source, name + ": resolution must be positive");
  for (double v : {cam.fx, cam.fy, cam.cx, cam.cy}) {
    if (!std::isfinite(v)) throw InputError(source, name + ": intrinsics are not finite");
  }
  if (cam.fx <= 0 || cam.fy <= 0) throw InputError(source, name + ": focal lengths must be positive");
  const size_t expected = cam.distortion == DistortionModel::kNone ? 0 : 4;
  if (cam.distortion_coeffs.size() != expected) {
    throw InputError(source, name + ": expected " + std::to_string(expected) + " distortion coefficients, got " +
                                 std::to_string(cam.distortion_coeffs.size()));
  }
  for (double v : cam.distortion_coeffs) {
    if (!std::isfinite(v)) throw InputError(source, name + ": distortion coefficients are not finite");
  }
}

void validate_pose(const SE3& T, const std::string& name, const std::string& source) {
  if (!T.matrix().allFinite()) throw InputError(source, name + " is not finite");
}

}  // namespace

void validate_calibration(const RigCalibration& calib, const std::string& source) {
  validate_camera(calib.cam0, "cam0", source);
  validate_camera(calib.cam1, "cam1", source);
  validate_pose(calib.T_I_C0, "T_I_C0", source);
  validate_pose(calib.T_I_C1, "T_I_C1", source);
  validate_pose(calib.T_I_L, "T_I_L", source);
  const ImuNoise& n = calib.imu;
  for (double v : {n.gyro_noise_density, n.gyro_random_walk, n.accel_noise_density, n.accel_random_walk, n.rate_hz}) {
    if (!std::isfinite(v) || v <= 0) throw InputError(source, "IMU noise parameters and rate must be positive");
  }
  if (calib.has_lidar && !(std::isfinite(calib.lidar.rate_hz) && calib.lidar.rate_hz > 0)) {
    throw InputError(source, "lidar rate_hz must be positive");
  }
}

}  // namespace vilslam
