#include "sim/sim_config.h"

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <set>

#include "common/error.h"
#include "sim/lidar_beams.h"

namespace vilslam::sim {
namespace {

// Reads YAML maps into the config, naming the file in every error.
class Reader {
 public:
  explicit Reader(std::string file) : file_(std::move(file)) {}

  // Every key of `node` must be one of `known` (catches typos that would silently keep a default).
  void check_keys(const YAML::Node& node, const std::set<std::string>& known, const std::string& where) const {
    if (!node) return;
    if (!node.IsMap()) fail(where + " must be a map");
    for (const auto& kv : node) {
      const std::string key = kv.first.as<std::string>();
      if (!known.count(key)) fail("unknown key '" + key + "' in " + where);
    }
  }

  template <typename T>
  void get(const YAML::Node& node, const std::string& key, T& value) const {
    if (!node || !node[key]) return;
    try {
      value = node[key].as<T>();
    } catch (const YAML::Exception&) {
      fail("bad value for '" + key + "'");
    }
    if constexpr (std::is_floating_point_v<T>) {
      if (!std::isfinite(value)) fail("non-finite value for '" + key + "'");
    }
  }

  void get_vec3(const YAML::Node& node, const std::string& key, Vec3& value) const {
    std::vector<double> v;
    get(node, key, v);
    if (!node || !node[key]) return;
    if (v.size() != 3) fail("'" + key + "' needs 3 values");
    value = Vec3(v[0], v[1], v[2]);
  }

  void get_intervals(const YAML::Node& node, const std::string& key, std::vector<FaultInterval>& out) const {
    std::vector<std::vector<double>> rows;
    get(node, key, rows);
    for (const auto& r : rows) {
      if (r.size() != 2 || !(r[1] > r[0])) fail("'" + key + "' needs [begin_s, end_s] pairs with end > begin");
      out.push_back({r[0], r[1]});
    }
  }

  [[noreturn]] void fail(const std::string& problem) const { throw InputError(file_, problem); }

 private:
  std::string file_;
};

void read_camera(const Reader& r, const YAML::Node& n, SimConfig& c) {
  r.check_keys(n, {"width_px", "height_px", "fx", "fy", "cx", "cy", "rate_hz", "distortion_coeffs", "baseline_m",
                   "position_in_imu_m"},
               "camera");
  r.get(n, "width_px", c.camera.width_px);
  r.get(n, "height_px", c.camera.height_px);
  r.get(n, "fx", c.camera.fx);
  r.get(n, "fy", c.camera.fy);
  r.get(n, "cx", c.camera.cx);
  r.get(n, "cy", c.camera.cy);
  r.get(n, "rate_hz", c.camera.rate_hz);
  r.get(n, "distortion_coeffs", c.camera.distortion_coeffs);
  r.get(n, "baseline_m", c.stereo_baseline_m);
  r.get_vec3(n, "position_in_imu_m", c.p_I_C0_m);
  if (!c.camera.distortion_coeffs.empty() && c.camera.distortion_coeffs.size() != 4)
    r.fail("camera.distortion_coeffs needs 4 values (radtan k1 k2 p1 p2) or none");
  c.camera.distortion = c.camera.distortion_coeffs.empty() ? DistortionModel::kNone : DistortionModel::kRadTan;
}

void read_imu(const Reader& r, const YAML::Node& n, SimConfig& c) {
  r.check_keys(n, {"rate_hz", "gyro_noise_density", "gyro_random_walk", "accel_noise_density", "accel_random_walk",
                   "add_noise", "initial_gyro_bias_sigma", "initial_accel_bias_sigma", "min_noise_factor",
                   "max_noise_factor", "max_scale_error", "max_misalignment_deg", "max_g_sensitivity"},
               "imu");
  r.get(n, "rate_hz", c.imu.noise.rate_hz);
  r.get(n, "gyro_noise_density", c.imu.noise.gyro_noise_density);
  r.get(n, "gyro_random_walk", c.imu.noise.gyro_random_walk);
  r.get(n, "accel_noise_density", c.imu.noise.accel_noise_density);
  r.get(n, "accel_random_walk", c.imu.noise.accel_random_walk);
  r.get(n, "add_noise", c.imu.add_noise);
  r.get(n, "initial_gyro_bias_sigma", c.imu.initial_gyro_bias_sigma);
  r.get(n, "initial_accel_bias_sigma", c.imu.initial_accel_bias_sigma);
  r.get(n, "min_noise_factor", c.imu.errors.min_noise_factor);
  r.get(n, "max_noise_factor", c.imu.errors.max_noise_factor);
  r.get(n, "max_scale_error", c.imu.errors.max_scale_error);
  r.get(n, "max_misalignment_deg", c.imu.errors.max_misalignment_deg);
  r.get(n, "max_g_sensitivity", c.imu.errors.max_g_sensitivity_rad_s_per_m_s2);
}

void read_lidar(const Reader& r, const YAML::Node& n, SimConfig& c) {
  r.check_keys(n, {"sensor", "num_rings", "min_elevation_deg", "max_elevation_deg", "azimuth_step_deg", "rate_hz",
                   "min_range_m", "max_range_m", "range_noise_sigma_m", "position_in_imu_m", "range_at_10pct_m",
                   "beam_divergence_rad", "mixed_pixel_probability", "mixed_pixel_min_jump_m"},
               "lidar");
  // The sensor model first: it sets every field, which the other keys may then override.
  std::string sensor;
  r.get(n, "sensor", sensor);
  if (!sensor.empty()) {
    try {
      c.lidar = lidar_sensor(sensor);
    } catch (const std::invalid_argument& e) {
      r.fail(std::string("lidar.sensor: ") + e.what());
    }
  }
  r.get(n, "num_rings", c.lidar.num_rings);
  r.get(n, "min_elevation_deg", c.lidar.min_elevation_deg);
  r.get(n, "max_elevation_deg", c.lidar.max_elevation_deg);
  r.get(n, "azimuth_step_deg", c.lidar.azimuth_step_deg);
  r.get(n, "rate_hz", c.lidar.rate_hz);
  r.get(n, "min_range_m", c.lidar.min_range_m);
  r.get(n, "max_range_m", c.lidar.max_range_m);
  r.get(n, "range_noise_sigma_m", c.lidar.range_noise_sigma_m);
  r.get(n, "range_at_10pct_m", c.lidar.returns.range_at_10pct_m);
  r.get(n, "beam_divergence_rad", c.lidar.returns.beam_divergence_rad);
  r.get(n, "mixed_pixel_probability", c.lidar.returns.mixed_pixel_probability);
  r.get(n, "mixed_pixel_min_jump_m", c.lidar.returns.mixed_pixel_min_jump_m);
  r.get_vec3(n, "position_in_imu_m", c.p_I_L_m);
}

void read_render(const Reader& r, const YAML::Node& n, SimConfig& c) {
  r.check_keys(n, {"noise_sigma_grey", "motion_blur_samples", "anisotropic_samples", "exposure_time_s",
                   "exposure_variation", "exposure_period_s", "vignetting"},
               "render");
  r.get(n, "vignetting", c.render.vignetting);
  r.get(n, "noise_sigma_grey", c.render.noise_sigma_grey);
  r.get(n, "motion_blur_samples", c.render.motion_blur_samples);
  r.get(n, "anisotropic_samples", c.render.anisotropic_samples);
  r.get(n, "exposure_time_s", c.render.exposure_time_s);
  r.get(n, "exposure_variation", c.exposure_variation);
  r.get(n, "exposure_period_s", c.exposure_period_s);
}

void read_motion(const Reader& r, const YAML::Node& n, SimConfig& c) {
  r.check_keys(n, {"indoor_speed_m_s", "outdoor_speed_m_s", "ramp_s", "outdoor_ramp_s", "rest_start_s", "rest_end_s",
                   "control_spacing_m", "outdoor_control_spacing_m", "roll_amplitude_deg", "pitch_amplitude_deg",
                   "sway_wavelength_m", "knot_spacing_s", "start_time_ns"},
               "motion");
  r.get(n, "indoor_speed_m_s", c.motion.cruise_speed_m_s);
  r.get(n, "outdoor_speed_m_s", c.outdoor_speed_m_s);
  r.get(n, "ramp_s", c.motion.ramp_s);
  r.get(n, "outdoor_ramp_s", c.outdoor_ramp_s);
  r.get(n, "rest_start_s", c.motion.rest_start_s);
  r.get(n, "rest_end_s", c.motion.rest_end_s);
  r.get(n, "control_spacing_m", c.motion.control_spacing_m);
  r.get(n, "outdoor_control_spacing_m", c.outdoor_control_spacing_m);
  r.get(n, "roll_amplitude_deg", c.motion.roll_amplitude_deg);
  r.get(n, "pitch_amplitude_deg", c.motion.pitch_amplitude_deg);
  r.get(n, "sway_wavelength_m", c.motion.sway_wavelength_m);
  r.get(n, "knot_spacing_s", c.pose_spline.knot_spacing_s);
  r.get(n, "start_time_ns", c.start_time_ns);
}

void read_faults(const Reader& r, const YAML::Node& n, SimConfig& c) {
  r.check_keys(n, {"camera_blackouts", "lidar_dropouts", "imu_gaps", "exposure_jumps", "exposure_jump_gain"}, "faults");
  r.get_intervals(n, "camera_blackouts", c.faults.camera_blackouts);
  r.get_intervals(n, "lidar_dropouts", c.faults.lidar_dropouts);
  r.get_intervals(n, "imu_gaps", c.faults.imu_gaps);
  r.get_intervals(n, "exposure_jumps", c.faults.exposure_jumps);
  r.get(n, "exposure_jump_gain", c.faults.exposure_jump_gain);
}

void read_calibration_errors(const Reader& r, const YAML::Node& n, SimConfig& c) {
  r.check_keys(n, {"camera_rotation_deg", "camera_translation_m", "lidar_rotation_deg", "lidar_translation_m",
                   "camera_time_offset_s", "lidar_time_offset_s", "stereo_rotation_deg", "intrinsics_px"},
               "calibration_errors");
  CalibrationErrors& e = c.calibration_errors;
  r.get(n, "camera_rotation_deg", e.camera_rotation_deg);
  r.get(n, "camera_translation_m", e.camera_translation_m);
  r.get(n, "lidar_rotation_deg", e.lidar_rotation_deg);
  r.get(n, "lidar_translation_m", e.lidar_translation_m);
  r.get(n, "camera_time_offset_s", e.camera_time_offset_s);
  r.get(n, "lidar_time_offset_s", e.lidar_time_offset_s);
  r.get(n, "stereo_rotation_deg", e.stereo_rotation_deg);
  r.get(n, "intrinsics_px", e.intrinsics_px);
}

void validate(const Reader& r, const SimConfig& c) {
  const bool ok = c.camera.width_px > 0 && c.camera.height_px > 0 && c.camera.fx > 0 && c.camera.fy > 0 &&
                  c.camera.rate_hz > 0 && c.stereo_baseline_m > 0 && c.imu.noise.rate_hz > 0 && c.lidar.rate_hz > 0 &&
                  c.motion.cruise_speed_m_s > 0 &&
                  c.outdoor_speed_m_s > 0 && c.motion.ramp_s > 0 && c.outdoor_ramp_s > 0 &&
                  c.motion.control_spacing_m > 0 && c.outdoor_control_spacing_m > 0 &&
                  c.pose_spline.knot_spacing_s > 0 && c.render.motion_blur_samples >= 1 &&
                  c.render.anisotropic_samples >= 1 && c.preview_duration_s > 0 &&
                  c.model_spacing_m > 0 && c.parallel_batch > 0 && c.faults.exposure_jump_gain > 0;
  if (!ok) r.fail("rates, sizes, speeds, spacings and counts must be positive");
  const CalibrationErrors& e = c.calibration_errors;
  const LidarReturnModel& m = c.lidar.returns;
  if (!(c.render.vignetting >= 0 && c.render.vignetting <= 1)) r.fail("render.vignetting must be in [0, 1]");
  if (!(e.camera_rotation_deg >= 0 && e.camera_translation_m >= 0 && e.lidar_rotation_deg >= 0 &&
        e.lidar_translation_m >= 0 && e.stereo_rotation_deg >= 0 && e.intrinsics_px >= 0 &&
        std::isfinite(e.camera_time_offset_s) && std::isfinite(e.lidar_time_offset_s)))
    r.fail("calibration_errors: angles and distances must be >= 0, offsets finite");
  const ImuErrorRanges& imu = c.imu.errors;
  if (!(imu.min_noise_factor > 0 && imu.min_noise_factor <= imu.max_noise_factor && std::isfinite(imu.max_noise_factor) &&
        imu.max_scale_error >= 0 && imu.max_misalignment_deg >= 0 && imu.max_g_sensitivity_rad_s_per_m_s2 >= 0))
    r.fail("imu: 0 < min_noise_factor <= max_noise_factor; max_scale_error, max_misalignment_deg, max_g_sensitivity >= 0");
  if (!(m.range_at_10pct_m >= 0 && m.beam_divergence_rad >= 0 && m.mixed_pixel_probability >= 0 &&
        m.mixed_pixel_probability <= 1 && m.mixed_pixel_min_jump_m >= 0))
    r.fail("lidar: range_at_10pct_m, beam_divergence_rad, mixed_pixel_min_jump_m >= 0, mixed_pixel_probability in [0, 1]");
  try {
    check_lidar_config(c.lidar);
  } catch (const std::invalid_argument& e) {
    r.fail(e.what());
  }
}

}  // namespace

CameraIntrinsics default_camera() {
  CameraIntrinsics cam;
  cam.width_px = 752;
  cam.height_px = 480;
  cam.fx = cam.fy = 460.0;
  cam.cx = 375.5;
  cam.cy = 239.5;
  cam.rate_hz = 20.0;
  return cam;
}

RenderOptions default_render() {
  RenderOptions r;
  r.noise_sigma_grey = 2.0;
  r.motion_blur_samples = 1;
  r.exposure_time_s = 0.005;
  r.vignetting = 0.5;
  return r;
}

SimConfig load_sim_config(const std::string& path) {
  const Reader r(path);
  YAML::Node root;
  try {
    root = YAML::LoadFile(path);
  } catch (const YAML::BadFile&) {
    r.fail("cannot open the file");
  } catch (const YAML::Exception& e) {
    throw InputError(path, e.msg, e.mark.line + 1);
  }
  SimConfig c;
  if (root.IsNull()) return c;
  r.check_keys(root, {"camera", "imu", "lidar", "render", "motion", "faults", "sensor_realism", "calibration_errors",
                      "preview_duration_s", "model_spacing_m", "parallel_batch"},
               "the top level");
  read_camera(r, root["camera"], c);
  read_imu(r, root["imu"], c);
  read_lidar(r, root["lidar"], c);
  read_render(r, root["render"], c);
  read_motion(r, root["motion"], c);
  read_faults(r, root["faults"], c);
  r.get(root, "sensor_realism", c.sensor_realism);
  read_calibration_errors(r, root["calibration_errors"], c);
  r.get(root, "preview_duration_s", c.preview_duration_s);
  r.get(root, "model_spacing_m", c.model_spacing_m);
  r.get(root, "parallel_batch", c.parallel_batch);
  validate(r, c);
  return c;
}

SimConfig ideal_sensors(SimConfig config) {
  config.calibration_errors = no_calibration_errors();
  config.imu.errors = no_imu_errors();
  config.lidar.returns = ideal_returns();
  config.render.vignetting = 0;
  return config;
}

RouteMotionConfig route_motion_config(const SimConfig& config, Scenario scenario) {
  RouteMotionConfig c = config.motion;
  if (scenario == Scenario::kOutdoor) {
    c.cruise_speed_m_s = config.outdoor_speed_m_s;
    c.ramp_s = config.outdoor_ramp_s;
    c.control_spacing_m = config.outdoor_control_spacing_m;
  }
  c.start_ns = config.start_time_ns;
  return c;
}

RigCalibration rig_calibration(const SimConfig& config) {
  Mat3 R_I_C;
  R_I_C.col(0) = -Vec3::UnitY();
  R_I_C.col(1) = -Vec3::UnitZ();
  R_I_C.col(2) = Vec3::UnitX();
  RigCalibration calib;
  calib.cam0 = config.camera;
  calib.cam1 = config.camera;
  calib.T_I_C0 = SE3(R_I_C, config.p_I_C0_m);
  calib.T_I_C1 = SE3(R_I_C, config.p_I_C0_m + R_I_C * Vec3(config.stereo_baseline_m, 0, 0));
  calib.has_lidar = true;
  calib.T_I_L = SE3(Mat3::Identity(), config.p_I_L_m);
  calib.lidar.num_rings = config.lidar.num_rings;
  calib.lidar.rate_hz = config.lidar.rate_hz;
  calib.lidar.min_range_m = config.lidar.min_range_m;
  calib.lidar.max_range_m = config.lidar.max_range_m;
  calib.imu = config.imu.noise;
  return calib;
}

}  // namespace vilslam::sim
