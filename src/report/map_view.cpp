#include "report/map_view.h"

#include <stdexcept>

#include "report/decimate.h"

namespace vilslam::report {
namespace {

PointCloud shown_points(const PointCloud& map, std::size_t max_points) {
  if (map.points.empty()) throw std::invalid_argument("the map has no points");
  PointCloud shown;
  for (std::size_t i : decimated_indices(map.size(), max_points)) shown.points.push_back(map.points[i]);
  return shown;
}

}  // namespace

MapView map_view(const PointCloud& map, std::size_t max_points) {
  MapView view;
  view.p_map = shown_points(map, max_points).points;
  view.total_points = map.size();
  view.value_name = "height_m";
  for (const Eigen::Vector3f& p : view.p_map) view.value.push_back(p.z());
  return view;
}

MapView map_view_with_error(const PointCloud& map, const PointCloud& model, const eval::MapErrorConfig& config,
                            std::size_t max_points) {
  const PointCloud shown = shown_points(map, max_points);
  MapView view;
  view.mre = eval::compute_map_error(shown, map, model, config);
  view.p_map = shown.points;
  view.total_points = map.size();
  view.value_name = "mre_m";
  view.value = view.mre->per_point_m;
  return view;
}

}  // namespace vilslam::report
