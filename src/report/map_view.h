#pragma once
// The map for the report's 3D view: at most max_points points (every k-th), each with a value to colour it
// by: its height (z in the map's world, m) or, with a reference model, its MRE distance to the model (m;
// eval/map_error.h, the alignment found on the whole map).
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "eval/map_error.h"
#include "io/cloud_io.h"

namespace vilslam::report {

struct MapView {
  std::vector<Eigen::Vector3f> p_map;  // the shown points, in the map's world
  std::vector<float> value;            // one per shown point
  std::string value_name;              // "height_m" | "mre_m"
  std::size_t total_points = 0;        // of the whole map
  std::optional<eval::MapError> mre;   // with a model: the summary over the shown points (per_point_m = value)
};

// Throws std::invalid_argument on an empty map or model, or when max_points is 0.
MapView map_view(const PointCloud& map, std::size_t max_points);
MapView map_view_with_error(const PointCloud& map, const PointCloud& model, const eval::MapErrorConfig& config,
                            std::size_t max_points);

}  // namespace vilslam::report
