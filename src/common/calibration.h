#pragma once
// Rig calibration: cameras, IMU noise, extrinsics to the IMU frame I, time offsets.
#include <string>
#include <vector>

#include "common/lie.h"
#include "common/time.h"

namespace vilslam {

enum class DistortionModel { kNone, kRadTan, kEquidistant };

struct CameraIntrinsics {
  int width_px = 0;
  int height_px = 0;
  double fx = 0, fy = 0, cx = 0, cy = 0;
  DistortionModel distortion = DistortionModel::kNone;
  // radtan: k1 k2 p1 p2; equidistant: k1 k2 k3 k4 (as in EuRoC / Kalibr files).
  std::vector<double> distortion_coeffs;
  double rate_hz = 0;
};

struct ImuNoise {
  double gyro_noise_density = 1.6968e-4;   // rad/s/sqrt(Hz)
  double gyro_random_walk = 1.9393e-5;     // rad/s^2/sqrt(Hz)
  double accel_noise_density = 2.0e-3;     // m/s^2/sqrt(Hz)
  double accel_random_walk = 3.0e-3;       // m/s^3/sqrt(Hz)
  double rate_hz = 200;
};

struct LidarIntrinsics {
  int num_rings = 16;
  double rate_hz = 10;
  double min_range_m = 0.5;
  double max_range_m = 100;
};

struct RigCalibration {
  CameraIntrinsics cam0;
  CameraIntrinsics cam1;
  SE3 T_I_C0;
  SE3 T_I_C1;
  bool has_lidar = false;
  SE3 T_I_L;
  LidarIntrinsics lidar;
  ImuNoise imu;
  // Sensor clock offsets: t_imu = t_sensor + offset.
  TimeNs cam_time_offset_ns = 0;
  TimeNs lidar_time_offset_ns = 0;

  // Stereo extrinsic: maps points from the right camera into the left one.
  SE3 T_C0_C1() const { return T_I_C0.inverse() * T_I_C1; }
};

// Throws InputError(source, ...) when a value cannot be a calibration (non-positive focal lengths,
// wrong number of distortion coefficients, non-finite values). Rotations are already checked by the
// readers, which see the raw matrices.
void validate_calibration(const RigCalibration& calib, const std::string& source);

}  // namespace vilslam
