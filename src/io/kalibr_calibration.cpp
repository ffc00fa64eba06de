#include "io/kalibr_calibration.h"

#include <cmath>
#include <filesystem>

#include "common/error.h"
#include "common/log.h"
#include "io/calibration_io.h"
#include "io/yaml_util.h"

namespace vilslam {
namespace {

TimeNs seconds_to_ns(double s) { return static_cast<TimeNs>(std::llround(s * 1e9)); }

double optional_double(const YAML::Node& node, const std::string& key, const std::string& file, double fallback) {
  return node[key] ? yaml_double(node, key, file) : fallback;
}

// The flat imu.yaml Kalibr takes as input, or the imu0 section of the one its IMU-camera calibration writes.
ImuNoise read_kalibr_imu(const std::string& path) {
  const YAML::Node root = load_yaml_file(path);
  const YAML::Node imu = root.IsMap() && root["imu0"] ? yaml_section(root, "imu0", path) : root;
  ImuNoise noise;
  noise.accel_noise_density = yaml_double(imu, "accelerometer_noise_density", path);
  noise.accel_random_walk = yaml_double(imu, "accelerometer_random_walk", path);
  noise.gyro_noise_density = yaml_double(imu, "gyroscope_noise_density", path);
  noise.gyro_random_walk = yaml_double(imu, "gyroscope_random_walk", path);
  noise.rate_hz = yaml_double(imu, "update_rate", path);
  return noise;
}

}  // namespace

RigCalibration read_kalibr_camchain(const std::string& path, const std::string& imu_path) {
  const YAML::Node root = load_yaml_file(path);
  RigCalibration calib;
  CameraIntrinsics* cams[2] = {&calib.cam0, &calib.cam1};
  SE3* T_I_C[2] = {&calib.T_I_C0, &calib.T_I_C1};
  for (int i = 0; i < 2; ++i) {
    const std::string name = "cam" + std::to_string(i);
    const YAML::Node node = yaml_section(root, name, path);
    *cams[i] = read_pinhole(node, path, "distortion_coeffs");
    if (node["T_cam_imu"]) {
      *T_I_C[i] = yaml_transform(node, "T_cam_imu", path).inverse();
    } else if (i == 1 && node["T_cn_cnm1"]) {
      // T_I_C1 = T_I_C0 T_C0_C1, with T_cn_cnm1 = T_C1_C0.
      *T_I_C[i] = calib.T_I_C0 * yaml_transform(node, "T_cn_cnm1", path).inverse();
    } else if (i == 1) {
      throw InputError(path, "cam1 needs T_cam_imu or T_cn_cnm1");
    }
  }
  calib.cam_time_offset_ns = seconds_to_ns(optional_double(root["cam0"], "timeshift_cam_imu", path, 0.0));
  if (!imu_path.empty()) calib.imu = read_kalibr_imu(imu_path);
  validate_calibration(calib, path);
  return calib;
}

void read_lidar_imu_yaml(const std::string& path, RigCalibration& calib) {
  const YAML::Node node = load_yaml_file(path);
  calib.has_lidar = true;
  calib.T_I_L = yaml_transform(node, "T_lidar_imu", path).inverse();
  calib.lidar_time_offset_ns = seconds_to_ns(optional_double(node, "timeshift_lidar_imu", path, 0.0));
  LidarIntrinsics& lidar = calib.lidar;
  lidar.num_rings = node["num_rings"] ? yaml_int(node, "num_rings", path) : lidar.num_rings;
  lidar.rate_hz = optional_double(node, "rate_hz", path, lidar.rate_hz);
  lidar.min_range_m = optional_double(node, "min_range_m", path, lidar.min_range_m);
  lidar.max_range_m = optional_double(node, "max_range_m", path, lidar.max_range_m);
}

KalibrFiles kalibr_files_beside(const std::string& camchain_path) {
  namespace fs = std::filesystem;
  const fs::path camchain(camchain_path);
  // camchain-imucam.yaml -> imu.yaml; camchain-imucam-NAME.yaml -> imu-NAME.yaml (likewise lidar-imu).
  const std::string name = camchain.filename().string();
  const std::string stem = "camchain-imucam";
  const std::string suffix = name.rfind(stem, 0) == 0 ? name.substr(stem.size()) : ".yaml";
  const auto beside = [&](const std::string& base) {
    const fs::path p = camchain.parent_path() / (base + suffix);
    return fs::exists(p) ? p.string() : std::string();
  };
  return {camchain_path, beside("imu"), beside("lidar-imu")};
}

bool is_kalibr_camchain(const std::string& path) {
  const YAML::Node root = load_yaml_file(path);
  return root.IsMap() && root["cam0"] && root["cam0"].IsMap() && !root["imu"] && !root["cam0"]["T_I_C"];
}

void apply_kalibr_files(const KalibrFiles& files, RigCalibration& calib) {
  const RigCalibration kalibr = read_kalibr_camchain(files.camchain, files.imu);
  const double rates_hz[2] = {calib.cam0.rate_hz, calib.cam1.rate_hz};
  calib.cam0 = kalibr.cam0;
  calib.cam1 = kalibr.cam1;
  calib.cam0.rate_hz = rates_hz[0];
  calib.cam1.rate_hz = rates_hz[1];
  calib.T_I_C0 = kalibr.T_I_C0;
  calib.T_I_C1 = kalibr.T_I_C1;
  calib.cam_time_offset_ns = kalibr.cam_time_offset_ns;
  if (!files.imu.empty()) calib.imu = kalibr.imu;
  if (!files.lidar.empty()) read_lidar_imu_yaml(files.lidar, calib);
  validate_calibration(calib, files.camchain);
}

std::map<std::string, std::string> kalibr_topics(const KalibrFiles& files) {
  std::map<std::string, std::string> topics;
  const auto take = [&](const YAML::Node& node, const std::string& role, const std::string& file) {
    if (!node || !node.IsMap() || !node["rostopic"]) return;
    if (!node["rostopic"].IsScalar()) throw InputError(file, "rostopic of " + role + " is not a topic name");
    topics[role] = node["rostopic"].Scalar();
  };
  const YAML::Node camchain = load_yaml_file(files.camchain);
  take(camchain["cam0"], "cam0", files.camchain);
  take(camchain["cam1"], "cam1", files.camchain);
  if (!files.imu.empty()) {
    const YAML::Node imu = load_yaml_file(files.imu);
    take(imu.IsMap() && imu["imu0"] ? imu["imu0"] : imu, "imu0", files.imu);
  }
  if (!files.lidar.empty()) take(load_yaml_file(files.lidar), "lidar0", files.lidar);
  return topics;
}

bool apply_kalibr_folder(const std::string& folder, RigCalibration& calib) {
  namespace fs = std::filesystem;
  const fs::path camchain = fs::path(folder) / kKalibrCamchainFile;
  if (!fs::exists(camchain)) return false;
  apply_kalibr_files(kalibr_files_beside(camchain.string()), calib);
  spdlog::info("calibration from Kalibr files in {}", folder);
  return true;
}

}  // namespace vilslam
