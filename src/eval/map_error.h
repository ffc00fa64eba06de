#pragma once
// Map registration error (MRE): the map cloud is aligned rigidly to the reference model by ICP,
// then each map point's error is its distance to the nearest model point.
#include <cstddef>
#include <vector>

#include "eval/icp.h"
#include "io/cloud_io.h"

namespace vilslam::eval {

struct MapErrorConfig {
  bool align = true;  // false: errors of the map as given, without ICP
  IcpConfig icp;
  // ICP aligns every k-th map point, k chosen so that at most this many take part (0: all). A 1 cm
  // dense map holds tens of millions of points, far more than a rigid alignment needs; the errors are
  // still computed for every point.
  std::size_t max_icp_points = 200000;
};

struct MapError {
  std::vector<float> per_point_m;  // one per map point, in map order
  double mean_m = 0, median_m = 0, p95_m = 0;
  IcpResult icp;                   // identity pose and 0 iterations when not aligned
};

// Throws std::invalid_argument on an empty map or model.
MapError compute_map_error(const PointCloud& map, const PointCloud& model, const MapErrorConfig& config);

}  // namespace vilslam::eval
