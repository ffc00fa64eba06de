#include "sim/scene_builder.h"

namespace vilslam::sim {

int SceneBuilder::material(Material::Kind kind, float base_grey, float contrast) {
  scene_.materials.push_back(Material{kind, base_grey, contrast, rng_.next()});
  return static_cast<int>(scene_.materials.size()) - 1;
}

}  // namespace vilslam::sim
