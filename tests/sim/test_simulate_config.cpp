#include <gtest/gtest.h>

#include <fstream>

#include "common/error.h"
#include "sim/sim_config.h"
#include "test_util.h"

namespace vilslam::sim {
namespace {

std::string write_yaml(const std::string& text) {
  const auto path = test::temp_dir() / "sim.yaml";
  std::ofstream(path) << text;
  return path.string();
}

TEST(SimConfig, DefaultFileListsTheDefaults) {
  const SimConfig file = load_sim_config(std::string(VILSLAM_SOURCE_DIR) + "/config/sim_default.yaml");
  const SimConfig def;
  EXPECT_EQ(file.camera.width_px, def.camera.width_px);
  EXPECT_EQ(file.camera.fx, def.camera.fx);
  EXPECT_EQ(file.camera.cx, def.camera.cx);
  EXPECT_EQ(file.camera.rate_hz, def.camera.rate_hz);
  EXPECT_EQ(file.camera.distortion, DistortionModel::kNone);
  EXPECT_EQ(file.stereo_baseline_m, def.stereo_baseline_m);
  EXPECT_EQ(file.p_I_C0_m, def.p_I_C0_m);
  EXPECT_EQ(file.p_I_L_m, def.p_I_L_m);
  EXPECT_EQ(file.imu.noise.gyro_noise_density, def.imu.noise.gyro_noise_density);
  EXPECT_EQ(file.imu.noise.accel_random_walk, def.imu.noise.accel_random_walk);
  EXPECT_EQ(file.imu.initial_accel_bias_sigma, def.imu.initial_accel_bias_sigma);
  EXPECT_EQ(file.lidar.azimuth_step_deg, def.lidar.azimuth_step_deg);
  EXPECT_EQ(file.render.noise_sigma_grey, def.render.noise_sigma_grey);
  EXPECT_EQ(file.exposure_variation, def.exposure_variation);
  EXPECT_EQ(file.motion.cruise_speed_m_s, def.motion.cruise_speed_m_s);
  EXPECT_EQ(file.motion.control_spacing_m, def.motion.control_spacing_m);
  EXPECT_EQ(file.outdoor_speed_m_s, def.outdoor_speed_m_s);
  EXPECT_EQ(file.pose_spline.knot_spacing_s, def.pose_spline.knot_spacing_s);
  EXPECT_EQ(file.start_time_ns, def.start_time_ns);
  EXPECT_EQ(file.preview_duration_s, def.preview_duration_s);
  EXPECT_EQ(file.sensor_realism, def.sensor_realism);
  EXPECT_EQ(file.render.vignetting, def.render.vignetting);
  EXPECT_EQ(file.render.motion_blur_samples, def.render.motion_blur_samples);
  EXPECT_EQ(file.render.anisotropic_samples, def.render.anisotropic_samples);
  EXPECT_EQ(file.lidar.returns.range_at_10pct_m, def.lidar.returns.range_at_10pct_m);
  EXPECT_EQ(file.lidar.returns.beam_divergence_rad, def.lidar.returns.beam_divergence_rad);
  EXPECT_EQ(file.lidar.returns.mixed_pixel_probability, def.lidar.returns.mixed_pixel_probability);
  EXPECT_EQ(file.lidar.returns.mixed_pixel_min_jump_m, def.lidar.returns.mixed_pixel_min_jump_m);
  const CalibrationErrors& e = file.calibration_errors;
  EXPECT_EQ(e.camera_rotation_deg, def.calibration_errors.camera_rotation_deg);
  EXPECT_EQ(e.camera_translation_m, def.calibration_errors.camera_translation_m);
  EXPECT_EQ(e.lidar_rotation_deg, def.calibration_errors.lidar_rotation_deg);
  EXPECT_EQ(e.lidar_translation_m, def.calibration_errors.lidar_translation_m);
  EXPECT_EQ(e.camera_time_offset_s, def.calibration_errors.camera_time_offset_s);
  EXPECT_EQ(e.lidar_time_offset_s, def.calibration_errors.lidar_time_offset_s);
}

TEST(SimConfig, ReadsOverridesAndFaults) {
  const SimConfig c = load_sim_config(write_yaml(
      "camera: {fx: 300, distortion_coeffs: [-0.28, 0.07, 0.0002, 0.00002]}\n"
      "imu: {rate_hz: 400}\n"
      "faults: {camera_blackouts: [[2.0, 3.5]], imu_gaps: [[1, 1.2], [4, 5]]}\n"
      "calibration_errors: {lidar_time_offset_s: 0.01, camera_rotation_deg: 0}\n"
      "render: {anisotropic_samples: 8}\n"));
  EXPECT_EQ(c.render.anisotropic_samples, 8);
  EXPECT_EQ(c.camera.fx, 300);
  EXPECT_EQ(c.camera.fy, 460);
  EXPECT_EQ(c.camera.distortion, DistortionModel::kRadTan);
  EXPECT_EQ(c.imu.noise.rate_hz, 400);
  ASSERT_EQ(c.faults.camera_blackouts.size(), 1u);
  EXPECT_EQ(c.faults.camera_blackouts[0].end_s, 3.5);
  EXPECT_EQ(c.faults.imu_gaps.size(), 2u);
  EXPECT_EQ(c.calibration_errors.lidar_time_offset_s, 0.01);
  EXPECT_EQ(c.calibration_errors.camera_rotation_deg, 0);
  EXPECT_EQ(c.calibration_errors.camera_time_offset_s, CalibrationErrors{}.camera_time_offset_s);
  EXPECT_TRUE(in_fault(c.faults.imu_gaps, s_to_ns(4.5)));
  EXPECT_FALSE(in_fault(c.faults.imu_gaps, s_to_ns(3.0)));
}

TEST(SimConfig, SensorModelSetsTheLidarAndKeysOverrideIt) {
  const SimConfig c = load_sim_config(write_yaml("lidar: {sensor: mid360, max_range_m: 40}\n"));
  EXPECT_EQ(c.lidar.pattern, LidarPattern::kNonRepetitive);
  EXPECT_EQ(c.lidar.min_elevation_deg, -7.0);
  EXPECT_EQ(c.lidar.max_range_m, 40.0);
  EXPECT_EQ(rig_calibration(c).lidar.num_rings, 0);  // no rings
  EXPECT_EQ(load_sim_config(write_yaml("lidar: {sensor: hesai128}\n")).lidar.num_rings, 128);
  try {
    load_sim_config(write_yaml("lidar: {sensor: hdl64}\n"));
    FAIL() << "an unknown sensor must be rejected";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("unknown LiDAR model 'hdl64'"), std::string::npos) << e.what();
  }
  // A beam list that does not match the ring count.
  EXPECT_THROW(load_sim_config(write_yaml("lidar: {sensor: hesai128, num_rings: 64}\n")), InputError);
}

TEST(SimConfig, RejectsBadInput) {
  EXPECT_THROW(load_sim_config("/nonexistent/sim.yaml"), InputError);
  EXPECT_THROW(load_sim_config(write_yaml("camera: {fxx: 300}\n")), InputError);
  EXPECT_THROW(load_sim_config(write_yaml("camera: {fx: -1}\n")), InputError);
  EXPECT_THROW(load_sim_config(write_yaml("camera: {fx: abc}\n")), InputError);
  EXPECT_THROW(load_sim_config(write_yaml("camera: {distortion_coeffs: [0.1]}\n")), InputError);
  EXPECT_THROW(load_sim_config(write_yaml("faults: {imu_gaps: [[3, 1]]}\n")), InputError);
  EXPECT_THROW(load_sim_config(write_yaml("imu: [1, 2\n")), InputError);
  EXPECT_THROW(load_sim_config(write_yaml("render: {anisotropic_samples: 0}\n")), InputError);
}

TEST(SimConfig, RigLooksForwardWithTheBaseline) {
  const RigCalibration calib = rig_calibration(SimConfig{});
  // C0's optical axis is the body's forward axis; C1 is 0.3 m to the right (+x in C0).
  EXPECT_LT((calib.T_I_C0.rotation().col(2) - Vec3::UnitX()).norm(), 1e-12);
  EXPECT_LT((calib.T_C0_C1().translation() - Vec3(0.3, 0, 0)).norm(), 1e-12);
  EXPECT_LT((calib.T_C0_C1().rotation() - Mat3::Identity()).norm(), 1e-12);
  EXPECT_GT(calib.T_I_L.translation().z(), calib.T_I_C0.translation().z());
  EXPECT_NO_THROW(validate_calibration(calib, "sim"));
}

}  // namespace
}  // namespace vilslam::sim
