#pragma once
// What a world generator produces (shapes, materials, route) and the builder it fills: typed adders
// that give every shape its material and a random uv offset, and the seeded random source.
#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

#include "sim/rng.h"
#include "sim/shapes.h"
#include "sim/world.h"

namespace vilslam::sim {

struct Scene {
  std::vector<std::unique_ptr<Shape>> shapes;
  std::vector<Material> materials;
  std::vector<Vec3> route_W;
};

class SceneBuilder {
 public:
  explicit SceneBuilder(std::uint64_t seed) : rng_(seed) {}
  Rng& rng() { return rng_; }
  // A new material with its own texture seed.
  int material(Material::Kind kind, float base_grey, float contrast);
  // Adds a shape with every face of `material`; returns it to set per-face materials or decals.
  template <typename ShapeT>
  ShapeT& add(ShapeT shape, int material) {
    auto owned = std::make_unique<ShapeT>(std::move(shape));
    owned->face_material.assign(owned->face_material.size(), material);
    owned->uv_offset = Eigen::Vector2d(rng_.uniform(0, 100), rng_.uniform(0, 100));
    ShapeT& ref = *owned;
    scene_.shapes.push_back(std::move(owned));
    return ref;
  }
  void set_route(std::vector<Vec3> route_W) { scene_.route_W = std::move(route_W); }
  const std::vector<Vec3>& route() const { return scene_.route_W; }
  Scene finish() { return std::move(scene_); }

 private:
  Rng rng_;
  Scene scene_;
};

}  // namespace vilslam::sim
