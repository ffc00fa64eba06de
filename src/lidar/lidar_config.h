#pragma once
// Every tuning knob of LiDAR mapping in one value, with defaults; loadable from a short YAML file whose
// sections and keys mirror the struct fields (rings, features, map, registration), all optional.
#include <string>

#include "common/yaml_config.h"

#include "lidar/feature_map.h"
#include "lidar/features.h"
#include "lidar/registration.h"
#include "lidar/ring_assignment.h"

namespace vilslam::lidar {

struct LidarConfig {
  RingConfig rings;
  FeatureConfig features;
  FeatureMapConfig map;
  RegistrationConfig registration;
};

// The sections rings, features, map (edges, surfaces) and registration, bound to c's fields.
YamlFields lidar_yaml_fields(LidarConfig& c);

// c's feature settings as its registration needs them: ring normals only where the normal test uses them.
FeatureConfig features_for_registration(const LidarConfig& c);

// Throws InputError(source, ...) when a count or voxel size is not positive.
void validate_lidar_config(const LidarConfig& c, const std::string& source);

// A file of lidar_yaml_fields (e.g. config/lidar_hdl32e.yaml for `vilslam register`). Throws InputError
// naming the file on a missing file, bad YAML, unknown key, wrong value type or invalid value.
LidarConfig load_lidar_config(const std::string& path);

}  // namespace vilslam::lidar
