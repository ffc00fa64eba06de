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
constexpr int kBlockBits = kBits - VoxelBlock::kBitsPerAxis;
constexpr std::uint64_t kLocalMask = VoxelBlock::kSide - 1;

// Voxel index along one axis biased into [0, 2^21), or -1 when out of range.
std::int64_t biased_index(float coordinate, double voxel_size_m) {
  const double index = std::floor(static_cast<double>(coordinate) / voxel_size_m) + static_cast<double>(kBias);
  if (!(index >= 0.0 && index <= static_cast<double>(kFieldMask))) return -1;
  return static_cast<std::int64_t>(index);
}

// Voxel key: the three biased indices as 21-bit fields (x high, z low), so key order is lexicographic
// (x, y, z) index order; points() sorts by it.
std::uint64_t voxel_key(std::uint64_t ix, std::uint64_t iy, std::uint64_t iz) {
  return (ix << (2 * kBits)) | (iy << kBits) | iz;
}

std::uint64_t block_key(std::uint64_t ix, std::uint64_t iy, std::uint64_t iz) {
  constexpr int b = VoxelBlock::kBitsPerAxis;
  return ((ix >> b) << (2 * kBlockBits)) | ((iy >> b) << kBlockBits) | (iz >> b);
}

unsigned local_index(std::uint64_t ix, std::uint64_t iy, std::uint64_t iz) {
  return VoxelBlock::local_index(static_cast<unsigned>(ix & kLocalMask), static_cast<unsigned>(iy & kLocalMask),
                                 static_cast<unsigned>(iz & kLocalMask));
}

// Key of the voxel at local index `local` of the block with key `block`.
std::uint64_t voxel_key_in_block(std::uint64_t block, unsigned local) {
  constexpr int b = VoxelBlock::kBitsPerAxis;
  constexpr std::uint64_t block_field = (std::uint64_t{1} << kBlockBits) - 1;
  const std::uint64_t x = ((block >> (2 * kBlockBits)) << b) | (local >> (2 * b));
  const std::uint64_t y = (((block >> kBlockBits) & block_field) << b) | ((local >> b) & kLocalMask);
  const std::uint64_t z = ((block & block_field) << b) | (local & kLocalMask);
  return voxel_key(x, y, z);
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
    const auto x = static_cast<std::uint64_t>(ix), y = static_cast<std::uint64_t>(iy), z = static_cast<std::uint64_t>(iz);
    VoxelBlock::Voxel& v = blocks_[block_key(x, y, z)].find_or_add(local_index(x, y, z));
    if (v.count == 0) ++num_voxels_;
    ++v.count;
    v.mean_W += (p - v.mean_W) / static_cast<float>(v.count);  // running mean
    ++added;
  }
  inserted_ += added;
  return added;
}

std::vector<Eigen::Vector3f> DenseMap::points(std::uint32_t min_hits) const {
  std::vector<std::uint64_t> keys;
  keys.reserve(num_voxels_);
  for (const auto& [key, block] : blocks_) {
    const std::uint64_t this_block = key;  // C++17 lambdas cannot capture a structured binding (clang refuses)
    block.for_each([&](unsigned local, const VoxelBlock::Voxel& voxel) {
      if (voxel.count >= min_hits) keys.push_back(voxel_key_in_block(this_block, local));
    });
  }
  std::sort(keys.begin(), keys.end());
  constexpr std::uint64_t field = static_cast<std::uint64_t>(kFieldMask);
  std::vector<Eigen::Vector3f> out;
  out.reserve(keys.size());
  for (std::uint64_t key : keys) {
    const std::uint64_t x = key >> (2 * kBits), y = (key >> kBits) & field, z = key & field;
    out.push_back(blocks_.at(block_key(x, y, z)).find(local_index(x, y, z))->mean_W);
  }
  return out;
}

std::size_t DenseMap::memory_bytes() const {
  std::size_t bytes =
      blocks_.bucket_count() * sizeof(tsl::detail_robin_hash::bucket_entry<std::pair<std::uint64_t, VoxelBlock>, false>);
  for (const auto& [key, block] : blocks_) bytes += block.heap_bytes();
  return bytes;
}

}  // namespace vilslam::map
