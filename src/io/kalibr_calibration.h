#pragma once
// Kalibr calibration files (ethz-asl/kalibr), the calibration most real stereo-inertial datasets ship:
// camchain-imucam.yaml (cameras and camera-IMU extrinsics), imu.yaml (noise), and the project's small
// Kalibr-style lidar-imu.yaml for the LiDAR extrinsic (docs/formats.md). Kalibr's T_cam_imu maps IMU
// points into the camera frame (T_C_I), so T_I_C = T_cam_imu^-1; likewise T_I_L = T_lidar_imu^-1.
#include <map>
#include <string>

#include "common/calibration.h"

namespace vilslam {

// camchain(-imucam) YAML: cam0 and cam1 (pinhole, radtan | equidistant). T_I_C from T_cam_imu when present;
// otherwise cam0 is taken as I and cam1 placed by T_cn_cnm1 (= T_C1_C0). cam0's timeshift_cam_imu
// (s, t_imu = t_cam + shift) gives cam_time_offset_ns. Camera rates are not in Kalibr files (0).
// imu_path (optional): a Kalibr imu.yaml with the noise densities, random walks and update_rate (at the top
// level as Kalibr reads it, or under imu0 as its IMU-camera calibration writes it).
RigCalibration read_kalibr_camchain(const std::string& path, const std::string& imu_path = {});

// lidar-imu.yaml: T_lidar_imu (4x4) and optional timeshift_lidar_imu [s], num_rings, rate_hz, min_range_m,
// max_range_m; sets has_lidar, T_I_L, lidar_time_offset_ns and the given LiDAR intrinsics in calib.
void read_lidar_imu_yaml(const std::string& path, RigCalibration& calib);

// The Kalibr files a dataset folder may hold next to its data.
inline constexpr const char* kKalibrCamchainFile = "camchain-imucam.yaml";
inline constexpr const char* kKalibrImuFile = "imu.yaml";
inline constexpr const char* kLidarImuFile = "lidar-imu.yaml";

// A camchain file and the companions found beside it (empty when absent): imu.yaml and lidar-imu.yaml, or,
// for the names Kalibr gives its results (camchain-imucam-NAME.yaml), imu-NAME.yaml and lidar-imu-NAME.yaml.
struct KalibrFiles {
  std::string camchain, imu, lidar;
};
KalibrFiles kalibr_files_beside(const std::string& camchain_path);

// Whether a calibration YAML is a Kalibr camchain rather than a rig YAML (docs/formats.md): it has cam0 and
// neither a top-level imu section nor cam0's T_I_C.
bool is_kalibr_camchain(const std::string& path);

// Replaces the cameras, their extrinsics and time offset in calib by the camchain, the IMU noise by the imu
// file and the LiDAR by the lidar file when those are given (camera rates and whatever has no file stay),
// and validates.
void apply_kalibr_files(const KalibrFiles& files, RigCalibration& calib);

// The topics Kalibr's files name (`rostopic` of cam0, cam1 in the camchain, of the IMU in the imu file, and
// of the LiDAR file), by role (cam0, cam1, imu0, lidar0), those present.
std::map<std::string, std::string> kalibr_topics(const KalibrFiles& files);

// When folder holds camchain-imucam.yaml, apply_kalibr_files with its companions and returns true;
// otherwise false.
bool apply_kalibr_folder(const std::string& folder, RigCalibration& calib);

}  // namespace vilslam
