#include "sim/scene_builder.h"

namespace vilslam::sim {

std::uint64_t Rng::next() {
  std::uint64_t z = (state_ += 0x9E3779B97F4A7C15ull);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

double Rng::uniform(double lo, double hi) { return lo + (hi - lo) * static_cast<double>(next() >> 11) * 0x1.0p-53; }

int Rng::integer(int lo, int hi) { return lo + static_cast<int>(next() % static_cast<std::uint64_t>(hi - lo + 1)); }

int SceneBuilder::material(Material::Kind kind, float base_grey, float contrast) {
  scene_.materials.push_back(Material{kind, base_grey, contrast, rng_.next()});
  return static_cast<int>(scene_.materials.size()) - 1;
}

}  // namespace vilslam::sim
