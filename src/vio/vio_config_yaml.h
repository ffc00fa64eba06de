#pragma once
// VioConfig <-> YAML: the `vio:` section of a run config (pipeline/run_config.h). Keys mirror the struct:
// smoother (window_size, pixel_sigma_px, gravity_m_s2, outlier_normal_quantile, lm: max_iterations,
// initial_lambda, min_relative_decrease, min_step_norm), initializer (averaging_window_s,
// max_accel_std_m_s2, max_gyro_std_rad_s) and the first state's prior sigmas at the top level.
// The IMU noise of the preintegration comes from the rig calibration, not from here.
#include <string>

#include "common/yaml_config.h"
#include "vio/vio.h"

namespace vilslam {

// Bound to c's fields; read with read_yaml_fields, then validate.
YamlFields vio_yaml_fields(VioConfig& c);

// Throws InputError(source, ...) naming the key of a value out of its range.
void validate_vio_config(const VioConfig& c, const std::string& source);

}  // namespace vilslam
