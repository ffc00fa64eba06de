#pragma once
// Map registration error (MRE): the map cloud is aligned rigidly to the reference model by ICP,
// then each map point's error is its distance to the nearest model point.
#include <vector>

#include "eval/icp.h"
#include "io/cloud_io.h"

namespace vilslam::eval {

struct MapErrorConfig {
  bool align = true;  // false: errors of the map as given, without ICP
  IcpConfig icp;
};

struct MapError {
  std::vector<float> per_point_m;  // one per map point, in map order
  double mean_m = 0, median_m = 0, p95_m = 0;
  IcpResult icp;                   // identity pose and 0 iterations when not aligned
};

// Throws std::invalid_argument on an empty map or model.
MapError compute_map_error(const PointCloud& map, const PointCloud& model, const MapErrorConfig& config);

}  // namespace vilslam::eval
