#include "lidar/feature_map.h"

namespace vilslam::lidar {

std::vector<Vec3> transform_points(const std::vector<FeaturePoint>& points_L, const SE3& T_W_L) {
  std::vector<Vec3> points_W;
  points_W.reserve(points_L.size());
  for (const FeaturePoint& f : points_L) points_W.push_back(T_W_L * f.p_L);
  return points_W;
}

void FeatureMap::insert(const FeatureScan& features_L, const SE3& T_W_L) {
  edges.insert(transform_points(features_L.edges, T_W_L));
  surfaces.insert(transform_points(features_L.surfaces, T_W_L));
  edges.remove_far(T_W_L.translation());
  surfaces.remove_far(T_W_L.translation());
}

FeatureMap build_feature_map(const FeatureMapConfig& config, const std::vector<PosedFeatureScan>& scans,
                             const Vec3& sensor_W) {
  FeatureMap map(config);
  for (const PosedFeatureScan& scan : scans) {
    map.edges.insert(transform_points(scan.features_L->edges, scan.T_W_L));
    map.surfaces.insert(transform_points(scan.features_L->surfaces, scan.T_W_L));
  }
  map.edges.remove_far(sensor_W);
  map.surfaces.remove_far(sensor_W);
  return map;
}

}  // namespace vilslam::lidar
