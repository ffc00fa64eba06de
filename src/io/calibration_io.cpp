#include "io/calibration_io.h"

#include <cmath>
#include <limits>
#include <sstream>

#include "common/error.h"
#include "common/json_writer.h"
#include "io/yaml_util.h"

namespace vilslam {
namespace {

std::size_t coeff_count(DistortionModel model) { return model == DistortionModel::kNone ? 0 : 4; }

std::string transform_text(const SE3& T) {
  const std::vector<double> v = transform_entries(T);
  std::string out = "\n";
  for (int r = 0; r < 4; ++r) out += "    - " + yaml_list({v[4 * r], v[4 * r + 1], v[4 * r + 2], v[4 * r + 3]}) + "\n";
  return out;
}

std::string camera_text(const std::string& name, const CameraIntrinsics& c, const SE3& T_I_C) {
  std::ostringstream out;
  out << name << ":\n  camera_model: pinhole\n  resolution: [" << c.width_px << ", " << c.height_px << "]\n"
      << "  intrinsics: " << yaml_list({c.fx, c.fy, c.cx, c.cy}) << "\n"
      << "  distortion_model: " << distortion_model_name(c.distortion) << "\n"
      << "  distortion_coeffs: " << yaml_list(c.distortion_coeffs) << "\n"
      << "  rate_hz: " << yaml_number(c.rate_hz) << "\n"
      << "  T_I_C:" << transform_text(T_I_C);
  return out.str();
}

}  // namespace

CameraIntrinsics read_pinhole(const YAML::Node& node, const std::string& file, const std::string& coeffs_key) {
  const std::string model = yaml_string(node, "camera_model", file);
  if (model != "pinhole") throw InputError(file, "camera_model '" + model + "' is not supported (pinhole only)");
  CameraIntrinsics c;
  const std::vector<double> res = yaml_doubles(node, "resolution", file, 2);
  for (double v : res) {
    if (!(v >= 1 && v <= std::numeric_limits<int>::max()) || v != std::floor(v)) {
      throw InputError(file, "resolution: expected two positive integers");
    }
  }
  c.width_px = static_cast<int>(res[0]);
  c.height_px = static_cast<int>(res[1]);
  const std::vector<double> k = yaml_doubles(node, "intrinsics", file, 4);
  c.fx = k[0];
  c.fy = k[1];
  c.cx = k[2];
  c.cy = k[3];
  c.distortion = parse_distortion_model(yaml_string(node, "distortion_model", file), file);
  c.distortion_coeffs = yaml_doubles(node, coeffs_key, file, coeff_count(c.distortion));
  return c;
}

DistortionModel parse_distortion_model(const std::string& name, const std::string& file) {
  if (name == "radtan" || name == "radial-tangential" || name == "plumb_bob") return DistortionModel::kRadTan;
  if (name == "equidistant" || name == "equi") return DistortionModel::kEquidistant;
  if (name == "none") return DistortionModel::kNone;
  throw InputError(file, "unknown distortion model '" + name + "'");
}

std::string distortion_model_name(DistortionModel model) {
  switch (model) {
    case DistortionModel::kRadTan: return "radtan";
    case DistortionModel::kEquidistant: return "equidistant";
    case DistortionModel::kNone: break;
  }
  return "none";
}

RigCalibration read_rig_yaml(const std::string& path) {
  const YAML::Node root = load_yaml_file(path);
  RigCalibration calib;
  CameraIntrinsics* cams[2] = {&calib.cam0, &calib.cam1};
  SE3* T_I_C[2] = {&calib.T_I_C0, &calib.T_I_C1};
  for (int i = 0; i < 2; ++i) {
    const YAML::Node node = yaml_section(root, "cam" + std::to_string(i), path);
    *cams[i] = read_pinhole(node, path, "distortion_coeffs");
    cams[i]->rate_hz = yaml_double(node, "rate_hz", path);
    *T_I_C[i] = yaml_transform(node, "T_I_C", path);
  }
  const YAML::Node imu = yaml_section(root, "imu", path);
  calib.imu.gyro_noise_density = yaml_double(imu, "gyro_noise_density", path);
  calib.imu.gyro_random_walk = yaml_double(imu, "gyro_random_walk", path);
  calib.imu.accel_noise_density = yaml_double(imu, "accel_noise_density", path);
  calib.imu.accel_random_walk = yaml_double(imu, "accel_random_walk", path);
  calib.imu.rate_hz = yaml_double(imu, "rate_hz", path);
  calib.has_lidar = root["lidar"].IsDefined();
  if (calib.has_lidar) {
    const YAML::Node lidar = yaml_section(root, "lidar", path);
    calib.T_I_L = yaml_transform(lidar, "T_I_L", path);
    calib.lidar.num_rings = yaml_int(lidar, "num_rings", path);
    calib.lidar.rate_hz = yaml_double(lidar, "rate_hz", path);
    calib.lidar.min_range_m = yaml_double(lidar, "min_range_m", path);
    calib.lidar.max_range_m = yaml_double(lidar, "max_range_m", path);
  }
  try {
    calib.cam_time_offset_ns = root["cam_time_offset_ns"] ? root["cam_time_offset_ns"].as<TimeNs>() : 0;
    calib.lidar_time_offset_ns = root["lidar_time_offset_ns"] ? root["lidar_time_offset_ns"].as<TimeNs>() : 0;
  } catch (const YAML::Exception&) {
    throw InputError(path, "time offsets must be integer nanoseconds");
  }
  validate_calibration(calib, path);
  return calib;
}

std::string rig_yaml_text(const RigCalibration& calib) {
  std::ostringstream out;
  out << "# vilslam rig calibration (docs/formats.md). T_a_b maps points from frame b into frame a;\n"
      << "# I = IMU body frame, C = camera (x right, y down, z forward), L = LiDAR. SI units.\n"
      << camera_text("cam0", calib.cam0, calib.T_I_C0) << camera_text("cam1", calib.cam1, calib.T_I_C1)
      << "imu:\n  gyro_noise_density: " << yaml_number(calib.imu.gyro_noise_density)
      << "\n  gyro_random_walk: " << yaml_number(calib.imu.gyro_random_walk)
      << "\n  accel_noise_density: " << yaml_number(calib.imu.accel_noise_density)
      << "\n  accel_random_walk: " << yaml_number(calib.imu.accel_random_walk)
      << "\n  rate_hz: " << yaml_number(calib.imu.rate_hz) << "\n";
  if (calib.has_lidar) {
    out << "lidar:\n  T_I_L:" << transform_text(calib.T_I_L) << "  num_rings: " << calib.lidar.num_rings
        << "\n  rate_hz: " << yaml_number(calib.lidar.rate_hz)
        << "\n  min_range_m: " << yaml_number(calib.lidar.min_range_m)
        << "\n  max_range_m: " << yaml_number(calib.lidar.max_range_m) << "\n";
  }
  out << "cam_time_offset_ns: " << calib.cam_time_offset_ns << "\nlidar_time_offset_ns: " << calib.lidar_time_offset_ns
      << "\n";
  return out.str();
}

void write_rig_yaml(const std::string& path, const RigCalibration& calib) {
  write_file_atomic(path, rig_yaml_text(calib));
}

}  // namespace vilslam
