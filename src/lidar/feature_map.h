#pragma once
// The local feature map of LiDAR mapping: edge points and surface points in the world frame, each in its
// own voxel map (the paper's "map (all previous feature points)", bounded around the sensor).
#include "lidar/features.h"
#include "lidar/voxel_map.h"

namespace vilslam::lidar {

struct FeatureMapConfig {
  VoxelMapConfig edges{1.0, 0.2, 20, 100.0};
  VoxelMapConfig surfaces{1.0, 0.4, 20, 100.0};
};

struct FeatureMap {
  explicit FeatureMap(const FeatureMapConfig& config = {}) : edges(config.edges), surfaces(config.surfaces) {}

  // Adds a dewarped feature scan taken at pose T_W_L, then forgets what is now far from the sensor.
  void insert(const FeatureScan& features_L, const SE3& T_W_L);

  VoxelMap edges;
  VoxelMap surfaces;
};

// A feature scan with the pose it is placed at.
struct PosedFeatureScan {
  const FeatureScan* features_L = nullptr;
  SE3 T_W_L;
};

// A map of several scans at their poses (in the given order), then limited to config's max_distance_m
// around sensor_W: the map that loop correction rebuilds from key scans (paper, "Re-localization").
FeatureMap build_feature_map(const FeatureMapConfig& config, const std::vector<PosedFeatureScan>& scans,
                             const Vec3& sensor_W);

// The feature points moved into the world frame by T_W_L.
std::vector<Vec3> transform_points(const std::vector<FeaturePoint>& points_L, const SE3& T_W_L);

}  // namespace vilslam::lidar
