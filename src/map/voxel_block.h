#pragma once
// A 16 x 16 x 16 cube of voxels that stores only its occupied ones: their local indices in increasing
// order and, at the same slots, their voxels. A surface crosses a block in a few dozen voxels, so the
// per-block cost (a hash table bucket, two array headers) is shared by many voxels, and a voxel costs
// 18 bytes (2 index + 12 mean + 4 count) plus growth slack.
#include <algorithm>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

namespace vilslam::map {

class VoxelBlock {
 public:
  static constexpr int kBitsPerAxis = 4;
  static constexpr int kSide = 1 << kBitsPerAxis;  // voxels per axis

  struct Voxel {
    Eigen::Vector3f mean_W = Eigen::Vector3f::Zero();
    std::uint32_t count = 0;
  };

  // Local index of the voxel (x, y, z) in [0, 16)^3: x * 256 + y * 16 + z, so its order is (x, y, z) order.
  static unsigned local_index(unsigned x, unsigned y, unsigned z) {
    return (x << (2 * kBitsPerAxis)) | (y << kBitsPerAxis) | z;
  }

  // The voxel at local_index; a new one (count 0) when it was not occupied.
  Voxel& find_or_add(unsigned local_index) {
    const auto it = std::lower_bound(locals_.begin(), locals_.end(), local_index);
    const std::ptrdiff_t slot = it - locals_.begin();
    if (it != locals_.end() && *it == local_index) return voxels_[static_cast<std::size_t>(slot)];
    // Grow by a quarter plus 4 slots instead of doubling, so little capacity stays unused.
    if (locals_.size() == locals_.capacity()) {
      const std::size_t capacity = locals_.size() + locals_.size() / 4 + 4;
      locals_.reserve(capacity);
      voxels_.reserve(capacity);
    }
    locals_.insert(locals_.begin() + slot, static_cast<std::uint16_t>(local_index));  // slot: reserve may have moved it
    return *voxels_.insert(voxels_.begin() + slot, Voxel{});
  }

  // The voxel at local_index, or nullptr when it is not occupied.
  const Voxel* find(unsigned local_index) const {
    const auto it = std::lower_bound(locals_.begin(), locals_.end(), local_index);
    if (it == locals_.end() || *it != local_index) return nullptr;
    return &voxels_[static_cast<std::size_t>(it - locals_.begin())];
  }

  // Calls f(local_index, voxel) for every occupied voxel in increasing local index.
  template <class F>
  void for_each(F&& f) const {
    for (std::size_t slot = 0; slot < locals_.size(); ++slot) f(unsigned{locals_[slot]}, voxels_[slot]);
  }

  // Heap bytes of the two arrays (their capacities); the block object itself is counted by its container.
  std::size_t heap_bytes() const {
    return locals_.capacity() * sizeof(std::uint16_t) + voxels_.capacity() * sizeof(Voxel);
  }

 private:
  std::vector<std::uint16_t> locals_;  // occupied voxels' local indices, increasing
  std::vector<Voxel> voxels_;          // voxels_[i] is the voxel at locals_[i]
};

}  // namespace vilslam::map
