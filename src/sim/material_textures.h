#pragma once
// The precomputed textures of a world's materials: per material a detail tile (kTexturePeriodM) and a
// macro tile (kMacroPeriodM), both mip-mapped, combined with cell shuffling so that surfaces do not
// visibly repeat. Lookups cost a few tens of nanoseconds.
#include <memory>
#include <vector>

#include <Eigen/Core>

#include "sim/mip_tile.h"
#include "sim/world.h"

namespace vilslam::sim {

struct TextureOptions {
  int detail_size = 1024;  // texels per side of the detail tile (4 mm texels; a quarter for plain paint)
  int macro_size = 256;
};

class MaterialTextures {
 public:
  explicit MaterialTextures(const std::vector<Material>& materials, const TextureOptions& options = {});

  // Albedo in [0, 1] of material `index` at uv (metres) seen with a pixel footprint of footprint_m.
  float albedo(int index, const Eigen::Vector2d& uv_m, double footprint_m) const;

 private:
  struct Entry {
    Material material;
    MipTile detail;
    MipTile macro;
  };
  float shuffled_detail(const Entry& e, const Eigen::Vector2d& uv_m, double footprint_m) const;
  std::vector<Entry> entries_;
};

// The textures of this material list, built on first use and shared (thread-safe; a few recent
// lists are kept, so alternating between two worlds does not rebuild).
std::shared_ptr<const MaterialTextures> material_textures(const std::vector<Material>& materials);

}  // namespace vilslam::sim
