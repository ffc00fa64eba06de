#pragma once
// LiDAR mapping's configuration for the sensor the data shows (issue 60): a run needs no per-sensor YAML. The
// built-in defaults are those of a spinning head with rings (VLP-16 class); a sweep whose returns fill the field
// of view without rings (a non-repetitive, Livox-type pattern) gets the neighbourhood features and the denser
// registration measured for that class (docs/lidar.md, "Sensors read from the data"). A key the user's config
// set to something other than its built-in default is kept: the per-sensor YAMLs are overrides.
#include "lidar/lidar_mapper.h"
#include "lidar/sensor_traits.h"

namespace vilslam::lidar {

LidarMapperConfig adapt_to_sensor(const LidarMapperConfig& given, const SensorTraits& traits);

}  // namespace vilslam::lidar
