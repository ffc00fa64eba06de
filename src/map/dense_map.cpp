#include "map/dense_map.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace vilslam::map {

namespace {

constexpr int kBits = 21;
constexpr std::int64_t kBias = std::int64_t{1} << (kBits - 1);
constexpr std::int64_t kFieldMask = (std::int64_t{1} << kBits) - 1;

// Voxel index along one axis biased into [0, 2^21), or -1 when out of range.
std::int64_t biased_index(float coordinate, double voxel_size_m) {
  const double index = std::floor(static_cast<double>(coordinate) / voxel_size_m) + static_cast<double>(kBias);
  if (!(index >= 0.0 && index <= static_cast<double>(kFieldMask))) return -1;
  return static_cast<std::int64_t>(index);
}

}  // namespace

DenseMap::DenseMap(double voxel_size_m) : voxel_size_m_(voxel_size_m) {
  if (!std::isfinite(voxel_size_m) || voxel_size_m <= 0.0) {
    throw std::invalid_argument("voxel size must be a positive number of metres, got " + std::to_string(voxel_size_m));
  }
}

std::size_t DenseMap::insert(const std::vector<Eigen::Vector3f>& points_W) {
  std::size_t added = 0;
  for (const Eigen::Vector3f& p : points_W) {
    if (!p.allFinite()) continue;
    const std::int64_t ix = biased_index(p.x(), voxel_size_m_);
    const std::int64_t iy = biased_index(p.y(), voxel_size_m_);
    const std::int64_t iz = biased_index(p.z(), voxel_size_m_);
    if (ix < 0 || iy < 0 || iz < 0) continue;
    const auto key = static_cast<std::uint64_t>((ix << (2 * kBits)) | (iy << kBits) | iz);
    Voxel& v = voxels_[key];
    ++v.count;
    v.mean_W += (p - v.mean_W) / static_cast<float>(v.count);  // running mean
    ++added;
  }
  inserted_ += added;
  return added;
}

std::vector<Eigen::Vector3f> DenseMap::points(std::uint32_t min_hits) const {
  std::vector<std::uint64_t> keys;
  keys.reserve(voxels_.size());
  for (const auto& [key, voxel] : voxels_) {
    if (voxel.count >= min_hits) keys.push_back(key);
  }
  std::sort(keys.begin(), keys.end());
  std::vector<Eigen::Vector3f> out;
  out.reserve(keys.size());
  for (std::uint64_t key : keys) out.push_back(voxels_.at(key).mean_W);
  return out;
}

std::size_t DenseMap::memory_bytes() const {
  return voxels_.bucket_count() * sizeof(tsl::detail_robin_hash::bucket_entry<std::pair<std::uint64_t, Voxel>, false>);
}

}  // namespace vilslam::map
