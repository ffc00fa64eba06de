#include "pipeline/run_config.h"

#include <cmath>

#include "common/yaml_config.h"
#include "vio/vio_config_yaml.h"

namespace vilslam {
namespace {

YamlFields graph_yaml_fields(loop::GlobalPoseGraphConfig& c) {
  return {yaml_value("odometry_sigma_m", c.odometry_sigma_m), yaml_value("odometry_sigma_rad", c.odometry_sigma_rad),
          yaml_value("degenerate_sigma", c.degenerate_sigma), yaml_value("tilt_sigma_rad", c.tilt_sigma_rad),
          yaml_value("tilt_final_only", c.tilt_final_only),
          yaml_value("bearing_min_step_m", c.bearing_min_step_m),
          yaml_value("loop_loss_scale", c.loop_loss_scale), yaml_value("max_iterations", c.max_iterations),
          yaml_value("anchor_spacing", c.anchor_spacing), yaml_value("max_anchors", c.max_anchors)};
}

YamlFields time_offset_yaml_fields(TimeOffsetConfig& c) {
  return {yaml_value("enabled", c.enabled),     yaml_value("online", c.online),
          yaml_value("update_every_s", c.update_every_s), yaml_value("online_window_s", c.online_window_s),
          yaml_value("window_s", c.window_s),
          yaml_value("max_abs_offset_s", c.max_abs_offset_s), yaml_value("grid_step_s", c.grid_step_s),
          yaml_value("min_rotation_rad_s", c.min_rotation_rad_s), yaml_value("min_intervals", c.min_intervals)};
}

YamlFields run_yaml_fields(OfflineRunConfig& c) {
  YamlFields loop_fields = loop::loop_closure_yaml_fields(c.loop);
  loop_fields.push_back(yaml_value("vocabulary", c.vocabulary));
  loop_fields.push_back(yaml_section("graph", graph_yaml_fields(c.graph)));
  return {yaml_section("frontend", frontend_yaml_fields(c.frontend)), yaml_section("vio", vio_yaml_fields(c.vio)),
          yaml_section("lidar_mapper", lidar::lidar_mapper_yaml_fields(c.lidar)),
          yaml_section("loop_closure", std::move(loop_fields)),
          yaml_section("time_offset", time_offset_yaml_fields(c.time_offset)),
          yaml_section("pipeline", {yaml_value("threads", c.threads), yaml_value("reset_on_lidar_lost", c.reset_on_lidar_lost),
                                    yaml_value("reset_check_s", c.reset_check_s)})};
}

void validate_time_offset_config(const TimeOffsetConfig& c, const std::string& path) {
  const auto positive = [&](double v, const char* key) {
    if (!(v > 0)) throw InputError(path, std::string("'time_offset.") + key + "' must be positive");
  };
  positive(c.window_s, "window_s");
  positive(c.update_every_s, "update_every_s");
  positive(c.online_window_s, "online_window_s");
  positive(c.max_abs_offset_s, "max_abs_offset_s");
  positive(c.grid_step_s, "grid_step_s");
  if (!(c.min_rotation_rad_s >= 0)) throw InputError(path, "'time_offset.min_rotation_rad_s' must be >= 0");
  if (c.min_intervals < 3) throw InputError(path, "'time_offset.min_intervals' must be at least 3");
  if (c.grid_step_s > c.max_abs_offset_s)
    throw InputError(path, "'time_offset.grid_step_s' must not exceed 'time_offset.max_abs_offset_s'");
}

void validate_graph_config(const loop::GlobalPoseGraphConfig& c, const std::string& path) {
  const auto positive = [&](double v, const char* key) {
    if (!(v > 0)) throw InputError(path, std::string("'loop_closure.graph.") + key + "' must be positive");
  };
  positive(c.odometry_sigma_m, "odometry_sigma_m");
  positive(c.odometry_sigma_rad, "odometry_sigma_rad");
  positive(c.loop_loss_scale, "loop_loss_scale");
  if (!(c.degenerate_sigma >= 0)) throw InputError(path, "'loop_closure.graph.degenerate_sigma' must be >= 0");
  if (!(c.tilt_sigma_rad >= 0)) throw InputError(path, "'loop_closure.graph.tilt_sigma_rad' must be >= 0");
  if (!(c.bearing_min_step_m >= 0) || !std::isfinite(c.bearing_min_step_m)) {
    throw InputError(path, "'loop_closure.graph.bearing_min_step_m' must be finite and >= 0");
  }
  if (c.max_iterations < 1) throw InputError(path, "'loop_closure.graph.max_iterations' must be at least 1");
  if (c.anchor_spacing < 1) throw InputError(path, "'loop_closure.graph.anchor_spacing' must be at least 1");
  if (c.max_anchors < 2) throw InputError(path, "'loop_closure.graph.max_anchors' must be at least 2");
}

}  // namespace

OfflineRunConfig load_run_config(const std::string& path) {
  OfflineRunConfig c;
  read_yaml_fields(load_yaml_file(path), path, "", run_yaml_fields(c));
  validate_frontend_config(c.frontend, path);
  validate_vio_config(c.vio, path);
  lidar::validate_lidar_config(c.lidar.lidar, path);
  loop::validate_loop_closure_config(c.loop, path);
  validate_graph_config(c.graph, path);
  validate_time_offset_config(c.time_offset, path);
  lidar::validate_mapping_loss_config(c.lidar.loss, path);
  if (!(c.reset_check_s > 0) || !std::isfinite(c.reset_check_s)) {
    throw InputError(path, "'pipeline.reset_check_s' must be positive and finite");
  }
  return c;
}

std::string run_config_yaml(const OfflineRunConfig& config) {
  OfflineRunConfig copy = config;
  YAML::Emitter out;
  out << write_yaml_fields(run_yaml_fields(copy));
  return std::string(out.c_str()) + "\n";
}

}  // namespace vilslam
