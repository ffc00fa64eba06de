#include "sim/material_textures.h"

#include <cmath>
#include <deque>
#include <mutex>
#include <utility>

#include "sim/procedural_noise.h"
#include "sim/texture.h"

namespace vilslam::sim {
namespace {

constexpr std::size_t kCachedLists = 3;

bool same_materials(const std::vector<Material>& a, const std::vector<Material>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (a[i].kind != b[i].kind || a[i].base_grey != b[i].base_grey || a[i].contrast != b[i].contrast ||
        a[i].seed != b[i].seed)
      return false;
  }
  return true;
}

// Weight of the cell itself at local coordinate f in [0, 1) of a cell of size cell_m, and the side
// (-1, 0, +1) of the neighbour it fades into within blend_m of the border.
std::pair<double, int> own_weight(double f, double cell_m, double blend_m) {
  const double to_border_m = std::min(f, 1 - f) * cell_m;
  if (blend_m <= 0 || to_border_m >= 0.5 * blend_m) return {1.0, 0};
  const double t = to_border_m / (0.5 * blend_m);
  return {0.5 + 0.5 * t * t * (3 - 2 * t), f < 0.5 ? -1 : 1};  // 0.5 on the border, 1 at blend_m / 2
}

}  // namespace

MaterialTextures::MaterialTextures(const std::vector<Material>& materials, const TextureOptions& options) {
  entries_.reserve(materials.size());
  for (const Material& m : materials) {
    // Plain paint has no detail finer than a few centimetres: a quarter of the texels suffice.
    const int detail_size = m.kind == Material::Kind::kPlain ? options.detail_size / 4 : options.detail_size;
    entries_.push_back(Entry{
        m,
        MipTile(detail_size, kTexturePeriodM,
                [&m](double u, double v, double texel_m) { return texture_albedo(m, {u, v}, texel_m); }),
        MipTile(options.macro_size, kMacroPeriodM,
                [&m](double u, double v, double) { return texture_macro_gain(m, {u, v}); })});
  }
}

float MaterialTextures::shuffled_detail(const Entry& e, const Eigen::Vector2d& uv_m, double footprint_m) const {
  const ShuffleCell sc = shuffle_cell(e.material.kind);
  if (sc.cells_u == 1 && sc.cells_v == 1) return e.detail.sample(uv_m.x(), uv_m.y(), footprint_m);
  const double cu = kTexturePeriodM / sc.cells_u, cv = kTexturePeriodM / sc.cells_v;
  const double X = uv_m.x() / cu, Y = uv_m.y() / cv;
  const auto i = static_cast<std::int64_t>(std::floor(X)), j = static_cast<std::int64_t>(std::floor(Y));
  const auto [wu, su] = own_weight(X - std::floor(X), cu, sc.blend_m);
  const auto [wv, sv] = own_weight(Y - std::floor(Y), cv, sc.blend_m);
  // Cell (a, b) shows the tile shifted by a random whole number of cells.
  auto lookup = [&](std::int64_t a, std::int64_t b) {
    const std::uint64_t h = hash64(e.material.seed + 0x5eed, a, b);
    const double du = cu * static_cast<double>(h % sc.cells_u), dv = cv * static_cast<double>((h >> 20) % sc.cells_v);
    return e.detail.sample(uv_m.x() + du, uv_m.y() + dv, footprint_m);
  };
  double value = wu * wv * lookup(i, j);
  if (su != 0) value += (1 - wu) * wv * lookup(i + su, j);
  if (sv != 0) value += wu * (1 - wv) * lookup(i, j + sv);
  if (su != 0 && sv != 0) value += (1 - wu) * (1 - wv) * lookup(i + su, j + sv);
  return static_cast<float>(value);
}

float MaterialTextures::albedo(int index, const Eigen::Vector2d& uv_m, double footprint_m) const {
  const Entry& e = entries_[index];
  const float gain = e.macro.sample_nearest_level(uv_m.x(), uv_m.y(), footprint_m);
  return std::min(1.0f, gain * shuffled_detail(e, uv_m, footprint_m));
}

std::shared_ptr<const MaterialTextures> material_textures(const std::vector<Material>& materials) {
  static std::mutex mutex;
  static std::deque<std::pair<std::vector<Material>, std::shared_ptr<const MaterialTextures>>> cache;
  std::lock_guard<std::mutex> lock(mutex);
  for (const auto& [key, textures] : cache) {
    if (same_materials(key, materials)) return textures;
  }
  auto textures = std::make_shared<const MaterialTextures>(materials);
  cache.emplace_front(materials, textures);
  if (cache.size() > kCachedLists) cache.pop_back();
  return textures;
}

}  // namespace vilslam::sim
