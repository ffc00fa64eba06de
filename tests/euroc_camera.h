#pragma once
// EuRoC's cam0 (752x480, radial-tangential) as in its sensor.yaml: the real camera several tests model.
#include "common/calibration.h"

namespace vilslam::test {

inline CameraIntrinsics euroc_cam0() {
  CameraIntrinsics cam;
  cam.width_px = 752;
  cam.height_px = 480;
  cam.fx = 458.654;
  cam.fy = 457.296;
  cam.cx = 367.215;
  cam.cy = 248.375;
  cam.distortion = DistortionModel::kRadTan;
  cam.distortion_coeffs = {-0.28340811, 0.07395907, 0.00019359, 1.76187114e-05};
  cam.rate_hz = 20;
  return cam;
}

}  // namespace vilslam::test
