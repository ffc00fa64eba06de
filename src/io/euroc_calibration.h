#pragma once
// EuRoC ASL sensor.yaml files (OpenCV "%YAML:1.0" style): each sensor's T_BS (sensor to body frame B)
// and its intrinsics. The body frame of EuRoC is the IMU frame (imu0's T_BS is the identity); readers
// compose T_I_S = T_B_I^-1 T_B_S so that a non-identity imu0 T_BS is handled too.
#include <string>

#include "common/calibration.h"

namespace vilslam {

struct EurocCamera {
  CameraIntrinsics intrinsics;
  SE3 T_B_C;
};

struct EurocImu {
  ImuNoise noise;
  SE3 T_B_I;
  bool from_file = false;  // false: the file was empty, defaults are used
};

struct EurocLidar {
  LidarIntrinsics intrinsics;
  SE3 T_B_L;
};

EurocCamera read_euroc_camera_yaml(const std::string& path);
// cam0 and cam1 of a mav0 folder into calib (intrinsics, T_I_C = T_B_I^-1 T_B_C).
void read_euroc_cameras(const std::string& mav0, const SE3& T_B_I, RigCalibration& calib);
EurocImu read_euroc_imu_yaml(const std::string& path);
EurocLidar read_euroc_lidar_yaml(const std::string& path);
// T_BS of any sensor.yaml (ground-truth "sensor"); identity when the file has none.
SE3 read_euroc_T_BS(const std::string& path);

// EuRoC-style sensor.yaml texts, used by the dataset writer next to rig.yaml.
std::string euroc_camera_yaml_text(const CameraIntrinsics& cam, const SE3& T_B_C, const std::string& comment);
std::string euroc_imu_yaml_text(const ImuNoise& noise);
std::string euroc_lidar_yaml_text(const LidarIntrinsics& lidar, const SE3& T_B_L);

}  // namespace vilslam
