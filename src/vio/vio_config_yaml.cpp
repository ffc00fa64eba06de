#include "vio/vio_config_yaml.h"

#include <cmath>

#include "common/error.h"

namespace vilslam {

YamlFields vio_yaml_fields(VioConfig& c) {
  SmootherConfig& s = c.smoother;
  LmConfig& lm = s.lm;
  InitializerConfig& i = c.initializer;
  ImuGapModel& g = c.imu_gap;
  VioLossConfig& l = c.loss;
  return {
      yaml_section("smoother",
                   {yaml_value("window_size", s.window_size), yaml_value("pixel_sigma_px", s.pixel_sigma_px),
                    yaml_value("gravity_m_s2", s.gravity_m_s2),
                    yaml_value("outlier_normal_quantile", s.outlier_normal_quantile),
                    yaml_section("lm", {yaml_value("max_iterations", lm.max_iterations),
                                        yaml_value("initial_lambda", lm.initial_lambda),
                                        yaml_value("min_relative_decrease", lm.min_relative_decrease),
                                        yaml_value("min_step_norm", lm.min_step_norm)})}),
      yaml_section("initializer", {yaml_value("averaging_window_s", i.averaging_window_s),
                                   yaml_value("max_accel_std_m_s2", i.max_accel_std_m_s2),
                                   yaml_value("max_gyro_std_rad_s", i.max_gyro_std_rad_s),
                                   yaml_value("moving_start", i.moving_start),
                                   yaml_section("alignment",
                                                {yaml_value("frames", i.alignment.frames),
                                                 yaml_value("min_pnp_inliers", i.alignment.min_pnp_inliers),
                                                 yaml_value("max_rotation_mismatch_rad", i.alignment.max_rotation_mismatch_rad),
                                                 yaml_value("max_gravity_error_m_s2", i.alignment.max_gravity_error_m_s2)})}),
      yaml_section("imu_gap", {yaml_value("max_step_s", g.max_step_s), yaml_value("rate_sigma_rad_s", g.rate_sigma_rad_s),
                               yaml_value("accel_sigma_m_s2", g.accel_sigma_m_s2)}),
      yaml_section("loss", {yaml_value("enabled", l.enabled), yaml_value("max_speed_m_s", l.max_speed_m_s),
                            yaml_value("max_gyro_bias_rad_s", l.max_gyro_bias_rad_s),
                            yaml_value("max_accel_bias_m_s2", l.max_accel_bias_m_s2),
                            yaml_value("min_frame_matches", l.min_frame_matches),
                            yaml_value("min_landmark_share", l.min_landmark_share),
                            yaml_value("max_cost_per_landmark", l.max_cost_per_landmark),
                            yaml_value("recent_states", l.recent_states),
                            yaml_value("inconsistent_states", l.inconsistent_states)}),
      yaml_value("prior_rotation_sigma_rad", c.prior_rotation_sigma_rad),
      yaml_value("moving_rotation_sigma_rad", c.moving_rotation_sigma_rad),
      yaml_value("prior_position_sigma_m", c.prior_position_sigma_m),
      yaml_value("prior_velocity_sigma_m_s", c.prior_velocity_sigma_m_s),
      yaml_value("moving_velocity_sigma_m_s", c.moving_velocity_sigma_m_s),
      yaml_value("prior_gyro_bias_sigma_rad_s", c.prior_gyro_bias_sigma_rad_s),
      yaml_value("prior_accel_bias_sigma_m_s2", c.prior_accel_bias_sigma_m_s2),
  };
}

void validate_vio_config(const VioConfig& c, const std::string& source) {
  const auto require = [&source](bool ok, const std::string& what) {
    if (!ok) throw InputError(source, "vio config: " + what);
  };
  const SmootherConfig& s = c.smoother;
  require(s.window_size >= 2, "smoother.window_size must be >= 2");
  require(s.pixel_sigma_px > 0, "smoother.pixel_sigma_px must be > 0");
  require(s.gravity_m_s2 > 0, "smoother.gravity_m_s2 must be > 0");
  require(s.outlier_normal_quantile > 0, "smoother.outlier_normal_quantile must be > 0");
  require(s.lm.max_iterations >= 1, "smoother.lm.max_iterations must be >= 1");
  require(s.lm.initial_lambda > 0, "smoother.lm.initial_lambda must be > 0");
  require(s.lm.min_relative_decrease >= 0, "smoother.lm.min_relative_decrease must be >= 0");
  require(s.lm.min_step_norm >= 0, "smoother.lm.min_step_norm must be >= 0");
  const InitializerConfig& i = c.initializer;
  require(i.averaging_window_s > 0, "initializer.averaging_window_s must be > 0");
  require(i.max_accel_std_m_s2 > 0, "initializer.max_accel_std_m_s2 must be > 0");
  require(i.max_gyro_std_rad_s > 0, "initializer.max_gyro_std_rad_s must be > 0");
  require(i.alignment.frames >= 3, "initializer.alignment.frames must be >= 3");
  require(i.alignment.min_pnp_inliers >= 4, "initializer.alignment.min_pnp_inliers must be >= 4");
  require(i.alignment.max_rotation_mismatch_rad > 0, "initializer.alignment.max_rotation_mismatch_rad must be > 0");
  require(i.alignment.max_gravity_error_m_s2 > 0, "initializer.alignment.max_gravity_error_m_s2 must be > 0");
  require(c.imu_gap.max_step_s > 0, "imu_gap.max_step_s must be > 0");
  require(c.imu_gap.rate_sigma_rad_s >= 0 && c.imu_gap.accel_sigma_m_s2 >= 0,
          "imu_gap.rate_sigma_rad_s and imu_gap.accel_sigma_m_s2 must be >= 0");
  const VioLossConfig& l = c.loss;
  require(l.max_speed_m_s > 0 && l.max_gyro_bias_rad_s > 0 && l.max_accel_bias_m_s2 > 0,
          "loss.max_speed_m_s, loss.max_gyro_bias_rad_s and loss.max_accel_bias_m_s2 must be > 0");
  require(l.min_frame_matches >= 1, "loss.min_frame_matches must be >= 1");
  require(l.min_landmark_share >= 0 && l.min_landmark_share <= 1, "loss.min_landmark_share must be in [0, 1]");
  require(l.max_cost_per_landmark > 0, "loss.max_cost_per_landmark must be > 0");
  require(l.inconsistent_states >= 1 && l.inconsistent_states <= l.recent_states,
          "loss.inconsistent_states must be in [1, loss.recent_states]");
  require(c.prior_rotation_sigma_rad > 0 && c.moving_rotation_sigma_rad > 0,
          "prior_rotation_sigma_rad and moving_rotation_sigma_rad must be > 0");
  require(c.prior_position_sigma_m > 0, "prior_position_sigma_m must be > 0");
  require(c.prior_velocity_sigma_m_s > 0 && c.moving_velocity_sigma_m_s > 0,
          "prior_velocity_sigma_m_s and moving_velocity_sigma_m_s must be > 0");
  require(c.prior_gyro_bias_sigma_rad_s > 0, "prior_gyro_bias_sigma_rad_s must be > 0");
  require(c.prior_accel_bias_sigma_m_s2 > 0, "prior_accel_bias_sigma_m_s2 must be > 0");
}

}  // namespace vilslam
