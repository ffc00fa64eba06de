#pragma once
// Every tuning knob of LiDAR mapping in one value, with defaults; loadable from a short YAML file whose
// sections and keys mirror the struct fields (rings, features, map, registration), all optional.
#include <string>

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

// Throws InputError naming the file on a missing file, bad YAML, unknown key or wrong value type.
LidarConfig load_lidar_config(const std::string& path);

}  // namespace vilslam::lidar
