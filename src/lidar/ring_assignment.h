#pragma once
// Splits a LiDAR sweep into rings (one per laser), each ordered by azimuth, as LOAM's feature extraction
// needs. Rings come from the scan's ring field, or from the elevation angle when the source had none.
#include <cstdint>
#include <vector>

#include "common/types.h"
#include "io/cloud_io.h"

namespace vilslam::lidar {

// The laser layout used when the ring must be derived from elevation: num_rings beams evenly spaced from
// min to max elevation (defaults: VLP-16). A Velodyne HDL-32E is 32 rings from -30.67 to +10.67 degrees.
struct RingConfig {
  int num_rings = 16;
  double min_elevation_deg = -15.0;
  double max_elevation_deg = 15.0;
  double min_range_m = 0.5;   // closer returns (the vehicle, empty returns at the origin) are dropped
  double max_range_m = 120.0;
};

// Indices into scan.points, one vector per ring, each sorted by azimuth (ties by index). With a ring field
// the scan's own ring numbers count (as many rings as its highest ring + 1, at least config.num_rings).
using Rings = std::vector<std::vector<std::uint32_t>>;

Rings assign_rings(const LidarScan& scan, const RingConfig& config);

// The share of the scan's points (within the range limits) whose elevation lies within a quarter ring
// spacing of a ring of config: near 1 for the configured spinning sensor, 0.5 for uniform elevations.
double fraction_on_rings(const LidarScan& scan, const RingConfig& config);

}  // namespace vilslam::lidar
