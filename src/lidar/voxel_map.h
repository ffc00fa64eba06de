#pragma once
// A sparse point map in a voxel hash: incremental insertion with per-voxel downsampling, neighbour search
// over the few voxels a query ball touches (no k-d tree to rebuild), and removal of far voxels so that memory
// is bounded by the mapped area around the sensor.
#include <Eigen/Core>
#include <tsl/robin_map.h>

#include <cstddef>
#include <vector>

#include "common/lie.h"

namespace vilslam::lidar {

// Teschner et al. (2003) spatial hash of an integer voxel key.
struct VoxelKeyHash {
  std::size_t operator()(const Eigen::Vector3i& v) const;
};

struct VoxelMapConfig {
  double voxel_size_m = 1.0;          // also the largest neighbour search radius that is exact
  double min_point_spacing_m = 0.2;   // a new point closer than this to one in its voxel is dropped
  int max_points_per_voxel = 20;
  double max_distance_m = 100.0;      // voxels farther than this from the sensor are removed
};

class VoxelMap {
 public:
  explicit VoxelMap(const VoxelMapConfig& config = {});

  void insert(const std::vector<Vec3>& points_W);
  // Drops every voxel whose centre is farther than config.max_distance_m from sensor_W.
  void remove_far(const Vec3& sensor_W);
  // Up to k points within radius_m of query_W, nearest first (ties by insertion order; deterministic).
  // radius_m is capped at the voxel size.
  std::vector<Vec3> nearest(const Vec3& query_W, int k, double radius_m) const;

  std::size_t num_points() const;
  std::size_t num_voxels() const { return voxels_.size(); }
  std::vector<Vec3> points() const;  // every map point, voxel by voxel in key order
  const VoxelMapConfig& config() const { return config_; }

 private:
  Eigen::Vector3i key_of(const Vec3& p) const;

  VoxelMapConfig config_;
  tsl::robin_map<Eigen::Vector3i, std::vector<Vec3>, VoxelKeyHash> voxels_;
};

// Keeps the first point of each voxel of side leaf_m (in input order): a deterministic downsampling.
std::vector<Vec3> voxel_downsample(const std::vector<Vec3>& points, double leaf_m);
// The same choice, as the indices of the kept points (ascending).
std::vector<std::size_t> voxel_downsample_indices(const std::vector<Vec3>& points, double leaf_m);

}  // namespace vilslam::lidar
