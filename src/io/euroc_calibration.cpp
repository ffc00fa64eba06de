#include "io/euroc_calibration.h"

#include <sstream>

#include "common/error.h"
#include "io/calibration_io.h"
#include "io/yaml_util.h"

namespace vilslam {
namespace {

std::string T_BS_text(const SE3& T) {
  const std::vector<double> v = transform_entries(T);
  std::ostringstream out;
  out << "T_BS:\n  cols: 4\n  rows: 4\n  data: [";
  for (std::size_t i = 0; i < v.size(); ++i) out << (i ? (i % 4 == 0 ? ",\n         " : ", ") : "") << yaml_number(v[i]);
  out << "]\n";
  return out.str();
}

}  // namespace

EurocCamera read_euroc_camera_yaml(const std::string& path) {
  const YAML::Node node = load_yaml_file(path);
  EurocCamera cam;
  cam.T_B_C = yaml_transform(node, "T_BS", path);
  CameraIntrinsics& c = cam.intrinsics;
  c = read_pinhole(node, path, "distortion_coefficients");
  c.rate_hz = node["rate_hz"] ? yaml_double(node, "rate_hz", path) : 0.0;
  return cam;
}

void read_euroc_cameras(const std::string& mav0, const SE3& T_B_I, RigCalibration& calib) {
  const EurocCamera left = read_euroc_camera_yaml(mav0 + "/cam0/sensor.yaml");
  const EurocCamera right = read_euroc_camera_yaml(mav0 + "/cam1/sensor.yaml");
  const SE3 T_I_B = T_B_I.inverse();
  calib.cam0 = left.intrinsics;
  calib.cam1 = right.intrinsics;
  calib.T_I_C0 = T_I_B * left.T_B_C;
  calib.T_I_C1 = T_I_B * right.T_B_C;
}

EurocImu read_euroc_imu_yaml(const std::string& path) {
  const YAML::Node node = load_yaml_file(path);
  EurocImu imu;
  if (node.IsNull()) return imu;
  imu.from_file = true;
  imu.T_B_I = yaml_transform(node, "T_BS", path);
  imu.noise.gyro_noise_density = yaml_double(node, "gyroscope_noise_density", path);
  imu.noise.gyro_random_walk = yaml_double(node, "gyroscope_random_walk", path);
  imu.noise.accel_noise_density = yaml_double(node, "accelerometer_noise_density", path);
  imu.noise.accel_random_walk = yaml_double(node, "accelerometer_random_walk", path);
  imu.noise.rate_hz = yaml_double(node, "rate_hz", path);
  return imu;
}

EurocLidar read_euroc_lidar_yaml(const std::string& path) {
  const YAML::Node node = load_yaml_file(path);
  EurocLidar lidar;
  lidar.T_B_L = yaml_transform(node, "T_BS", path);
  lidar.intrinsics.num_rings = yaml_int(node, "num_rings", path);
  lidar.intrinsics.rate_hz = yaml_double(node, "rate_hz", path);
  lidar.intrinsics.min_range_m = yaml_double(node, "min_range_m", path);
  lidar.intrinsics.max_range_m = yaml_double(node, "max_range_m", path);
  return lidar;
}

SE3 read_euroc_T_BS(const std::string& path) {
  const YAML::Node node = load_yaml_file(path);
  if (node.IsMap() && node["T_BS"]) return yaml_transform(node, "T_BS", path);
  return SE3::identity();
}

std::string euroc_camera_yaml_text(const CameraIntrinsics& cam, const SE3& T_B_C, const std::string& comment) {
  std::ostringstream out;
  out << "%YAML:1.0\nsensor_type: camera\ncomment: " << comment << "\n\n" << T_BS_text(T_B_C)
      << "\nrate_hz: " << yaml_number(cam.rate_hz) << "\nresolution: [" << cam.width_px << ", " << cam.height_px
      << "]\ncamera_model: pinhole\nintrinsics: " << yaml_list({cam.fx, cam.fy, cam.cx, cam.cy})
      << "\ndistortion_model: "
      << (cam.distortion == DistortionModel::kRadTan ? "radial-tangential" : distortion_model_name(cam.distortion))
      << "\ndistortion_coefficients: " << yaml_list(cam.distortion_coeffs) << "\n";
  return out.str();
}

std::string euroc_imu_yaml_text(const ImuNoise& noise) {
  std::ostringstream out;
  out << "%YAML:1.0\nsensor_type: imu\ncomment: IMU (defines the body frame)\n\n" << T_BS_text(SE3::identity())
      << "rate_hz: " << yaml_number(noise.rate_hz)
      << "\ngyroscope_noise_density: " << yaml_number(noise.gyro_noise_density)
      << "\ngyroscope_random_walk: " << yaml_number(noise.gyro_random_walk)
      << "\naccelerometer_noise_density: " << yaml_number(noise.accel_noise_density)
      << "\naccelerometer_random_walk: " << yaml_number(noise.accel_random_walk) << "\n";
  return out.str();
}

std::string euroc_lidar_yaml_text(const LidarIntrinsics& lidar, const SE3& T_B_L) {
  std::ostringstream out;
  out << "%YAML:1.0\nsensor_type: lidar\ncomment: spinning LiDAR\n\n" << T_BS_text(T_B_L)
      << "num_rings: " << lidar.num_rings << "\nrate_hz: " << yaml_number(lidar.rate_hz)
      << "\nmin_range_m: " << yaml_number(lidar.min_range_m) << "\nmax_range_m: " << yaml_number(lidar.max_range_m)
      << "\n";
  return out.str();
}

}  // namespace vilslam
