#pragma once
// Calibration files: the project's rig YAML (docs/formats.md) in and out, and the pinhole fields every
// camera calibration file shares (Kalibr: io/kalibr_calibration.h).
#include <yaml-cpp/yaml.h>

#include <string>

#include "common/calibration.h"

namespace vilslam {

// "radtan" / "radial-tangential" / "equidistant" / "none"; anything else is an InputError naming file.
DistortionModel parse_distortion_model(const std::string& name, const std::string& file);
// The project's name of a model: "radtan", "equidistant" or "none".
std::string distortion_model_name(DistortionModel model);

// The pinhole fields shared by Kalibr, EuRoC and rig files: resolution [w, h], intrinsics [fx, fy, cx, cy],
// distortion_model and the coefficient list named coeffs_key (EuRoC: distortion_coefficients).
// camera_model must be pinhole. rate_hz is left 0.
CameraIntrinsics read_pinhole(const YAML::Node& node, const std::string& file, const std::string& coeffs_key);

// The project's rig YAML (all RigCalibration fields).
RigCalibration read_rig_yaml(const std::string& path);
std::string rig_yaml_text(const RigCalibration& calib);
// Atomic (temporary file and rename).
void write_rig_yaml(const std::string& path, const RigCalibration& calib);

}  // namespace vilslam
