// VioConfig from YAML: every key reaches its field, bad values are InputErrors naming the key.
#include <gtest/gtest.h>

#include <string>

#include "common/error.h"
#include "test_util.h"
#include "vio/vio_config_yaml.h"

namespace vilslam {
namespace {

// A value different from the default for every key.
const char* kEveryKey = R"(
smoother:
  window_size: 7
  pixel_sigma_px: 1.5
  gravity_m_s2: 9.80665
  outlier_normal_quantile: 3.09
  lm:
    max_iterations: 25
    initial_lambda: 0.01
    min_relative_decrease: 1e-8
    min_step_norm: 1e-12
initializer:
  averaging_window_s: 0.5
  max_accel_std_m_s2: 0.4
  max_gyro_std_rad_s: 0.02
  moving_start: true
  alignment:
    frames: 12
    min_pnp_inliers: 20
    max_rotation_mismatch_rad: 0.03
    max_gravity_error_m_s2: 0.7
imu_gap:
  max_step_s: 0.1
  rate_sigma_rad_s: 0.5
  accel_sigma_m_s2: 2.0
loss:
  enabled: false
  max_speed_m_s: 20.0
  max_gyro_bias_rad_s: 0.2
  max_accel_bias_m_s2: 1.5
  min_frame_matches: 12
  min_landmark_share: 0.2
  max_cost_per_landmark: 30.0
  recent_states: 8
  inconsistent_states: 6
prior_rotation_sigma_rad: 0.03
moving_rotation_sigma_rad: 0.2
prior_position_sigma_m: 0.002
prior_velocity_sigma_m_s: 0.1
moving_velocity_sigma_m_s: 2.0
prior_gyro_bias_sigma_rad_s: 0.005
prior_accel_bias_sigma_m_s2: 0.3
)";

VioConfig read(const std::string& text) {
  VioConfig c;
  read_yaml_fields(YAML::Load(text), "vio.yaml", "", vio_yaml_fields(c));
  validate_vio_config(c, "vio.yaml");
  return c;
}

// Every key's value as YAML text.
std::string dump(VioConfig c) { return YAML::Dump(write_yaml_fields(vio_yaml_fields(c))); }

// The InputError message of reading text, or "" when it reads.
std::string error_of(const std::string& text) {
  try {
    read(text);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(VioConfigYaml, ReadsEveryKey) {
  EXPECT_EQ(test::yaml_key_paths(YAML::Load(kEveryKey)), test::yaml_key_paths(YAML::Load(dump(VioConfig{}))));
  const VioConfig c = read(kEveryKey);
  EXPECT_EQ(c.smoother.window_size, 7);
  EXPECT_EQ(c.smoother.pixel_sigma_px, 1.5);
  EXPECT_EQ(c.smoother.gravity_m_s2, 9.80665);
  EXPECT_EQ(c.smoother.outlier_normal_quantile, 3.09);
  EXPECT_EQ(c.smoother.lm.max_iterations, 25);
  EXPECT_EQ(c.smoother.lm.initial_lambda, 0.01);
  EXPECT_EQ(c.smoother.lm.min_relative_decrease, 1e-8);
  EXPECT_EQ(c.smoother.lm.min_step_norm, 1e-12);
  EXPECT_EQ(c.initializer.averaging_window_s, 0.5);
  EXPECT_EQ(c.initializer.max_accel_std_m_s2, 0.4);
  EXPECT_EQ(c.initializer.max_gyro_std_rad_s, 0.02);
  EXPECT_TRUE(c.initializer.moving_start);
  EXPECT_EQ(c.initializer.alignment.frames, 12);
  EXPECT_EQ(c.initializer.alignment.min_pnp_inliers, 20);
  EXPECT_EQ(c.initializer.alignment.max_rotation_mismatch_rad, 0.03);
  EXPECT_EQ(c.initializer.alignment.max_gravity_error_m_s2, 0.7);
  EXPECT_EQ(c.imu_gap.max_step_s, 0.1);
  EXPECT_EQ(c.imu_gap.rate_sigma_rad_s, 0.5);
  EXPECT_EQ(c.imu_gap.accel_sigma_m_s2, 2.0);
  EXPECT_FALSE(c.loss.enabled);
  EXPECT_EQ(c.loss.max_speed_m_s, 20.0);
  EXPECT_EQ(c.loss.max_gyro_bias_rad_s, 0.2);
  EXPECT_EQ(c.loss.max_accel_bias_m_s2, 1.5);
  EXPECT_EQ(c.loss.min_frame_matches, 12);
  EXPECT_EQ(c.loss.min_landmark_share, 0.2);
  EXPECT_EQ(c.loss.max_cost_per_landmark, 30.0);
  EXPECT_EQ(c.loss.recent_states, 8);
  EXPECT_EQ(c.loss.inconsistent_states, 6);
  EXPECT_EQ(c.prior_rotation_sigma_rad, 0.03);
  EXPECT_EQ(c.moving_rotation_sigma_rad, 0.2);
  EXPECT_EQ(c.prior_position_sigma_m, 0.002);
  EXPECT_EQ(c.prior_velocity_sigma_m_s, 0.1);
  EXPECT_EQ(c.moving_velocity_sigma_m_s, 2.0);
  EXPECT_EQ(c.prior_gyro_bias_sigma_rad_s, 0.005);
  EXPECT_EQ(c.prior_accel_bias_sigma_m_s2, 0.3);
  // Written back, every value reads again to the same config.
  EXPECT_EQ(dump(read(dump(c))), dump(c));
}

TEST(VioConfigYaml, MissingKeysKeepDefaults) {
  const VioConfig c = read("smoother:\n  window_size: 4\n");
  EXPECT_EQ(c.smoother.window_size, 4);
  VioConfig expected;
  expected.smoother.window_size = 4;
  EXPECT_EQ(dump(c), dump(expected));
  EXPECT_EQ(error_of(""), "");
}

TEST(VioConfigYaml, BadValuesNameTheKey) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"smoother:\n  window_size: -3\n", "smoother.window_size"},
      {"imu_gap:\n  max_step_s: 0\n", "imu_gap.max_step_s"},
      {"imu_gap:\n  accel_sigma_m_s2: -1\n", "imu_gap.accel_sigma_m_s2"},
      {"smoother:\n  window_size: 1\n", "smoother.window_size"},
      {"smoother:\n  window_size: 2.5\n", "smoother.window_size"},
      {"smoother:\n  window_size: ten\n", "smoother.window_size"},
      {"smoother:\n  pixel_sigma_px: .nan\n", "smoother.pixel_sigma_px"},
      {"smoother:\n  pixel_sigma_px: 0\n", "smoother.pixel_sigma_px"},
      {"smoother:\n  lm:\n    initial_lambda: .inf\n", "smoother.lm.initial_lambda"},
      {"smoother:\n  lm:\n    max_iterations: 0\n", "smoother.lm.max_iterations"},
      {"smoother:\n  windw_size: 4\n", "smoother.windw_size"},
      {"smoother: 4\n", "smoother"},
      {"initializer:\n  averaging_window_s: [1, 2]\n", "initializer.averaging_window_s"},
      {"initializer:\n  max_gyro_std_rad_s: -0.1\n", "initializer.max_gyro_std_rad_s"},
      {"initializer:\n  alignment:\n    frames: 2\n", "initializer.alignment.frames"},
      {"initializer:\n  moving_start: maybe\n", "initializer.moving_start"},
      {"loss:\n  min_landmark_share: 1.5\n", "loss.min_landmark_share"},
      {"loss:\n  inconsistent_states: 0\n", "loss.inconsistent_states"},
      {"loss:\n  inconsistent_states: 11\n", "loss.inconsistent_states"},
      {"loss:\n  max_cost_per_landmark: 0\n", "loss.max_cost_per_landmark"},
      {"loss:\n  max_speed_m_s: -1\n", "loss.max_speed_m_s"},
      {"prior_position_sigma_m: 0\n", "prior_position_sigma_m"},
      {"window_size: 4\n", "window_size"},
  };
  for (const auto& [text, key] : cases) {
    const std::string message = error_of(text);
    EXPECT_NE(message.find("vio.yaml"), std::string::npos) << text << " -> " << message;
    EXPECT_NE(message.find(key), std::string::npos) << text << " -> " << message;
  }
}

}  // namespace
}  // namespace vilslam
