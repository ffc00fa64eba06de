#pragma once
// The dense map of the paper's post processing: points in W averaged into cubic voxels (1 cm by default).
// A voxel is stored only once a point falls into it, so memory follows the occupied volume.
#include <cstdint>
#include <vector>

#include <Eigen/Core>
#include <tsl/robin_map.h>

#include "map/voxel_block.h"

namespace vilslam::map {

class DenseMap {
 public:
  // Throws std::invalid_argument unless voxel_size_m is finite and positive.
  explicit DenseMap(double voxel_size_m = 0.01);

  // Adds points in W; non-finite points and points beyond the index range (about +-10 km at 1 cm) are
  // not inserted. Returns how many were inserted.
  std::size_t insert(const std::vector<Eigen::Vector3f>& points_W);

  // The mean point of every voxel with at least min_hits points, in increasing voxel key order.
  std::vector<Eigen::Vector3f> points(std::uint32_t min_hits = 1) const;

  std::size_t num_voxels() const { return num_voxels_; }
  std::uint64_t num_points_inserted() const { return inserted_; }
  double voxel_size_m() const { return voxel_size_m_; }
  // Bytes held by the map: the block table's buckets (bucket count times bucket size) plus every block's
  // two arrays (capacity times 2 + 16 bytes). Allocator headers (two per block) are not counted.
  std::size_t memory_bytes() const;

 private:
  // Mixes all key bits into the low ones, which the power-of-two bucket mask keeps (splitmix64 finalizer).
  struct KeyHash {
    std::size_t operator()(std::uint64_t key) const {
      key = (key ^ (key >> 30)) * 0xbf58476d1ce4e5b9ULL;
      key = (key ^ (key >> 27)) * 0x94d049bb133111ebULL;
      return static_cast<std::size_t>(key ^ (key >> 31));
    }
  };

  double voxel_size_m_;
  // Key: the three block indices (voxel index / 16) as 17-bit fields, x high.
  tsl::robin_map<std::uint64_t, VoxelBlock, KeyHash> blocks_;
  std::size_t num_voxels_ = 0;
  std::uint64_t inserted_ = 0;
};

}  // namespace vilslam::map
