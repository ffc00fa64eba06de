#include "sim/world.h"

#include <algorithm>
#include <stdexcept>

#include "sim/bvh.h"
#include "sim/world_builders.h"

namespace vilslam::sim {

struct World::Impl {
  Scenario scenario = Scenario::kHighbay;
  Scene scene;
  Bvh bvh;
  Eigen::AlignedBox3d bounds;
};

Scenario parse_scenario(const std::string& name) {
  for (const Scenario s : {Scenario::kHighbay, Scenario::kHallway, Scenario::kTunnel, Scenario::kLoop,
                           Scenario::kOutdoor, Scenario::kRoom}) {
    if (scenario_name(s) == name) return s;
  }
  throw std::invalid_argument("unknown scenario '" + name + "' (highbay, hallway, tunnel, loop, outdoor, room)");
}

std::string scenario_name(Scenario scenario) {
  switch (scenario) {
    case Scenario::kHighbay: return "highbay";
    case Scenario::kHallway: return "hallway";
    case Scenario::kTunnel: return "tunnel";
    case Scenario::kLoop: return "loop";
    case Scenario::kOutdoor: return "outdoor";
    case Scenario::kRoom: return "room";
  }
  return "";
}

double preset_length_m(Scenario scenario) {
  switch (scenario) {
    case Scenario::kHighbay: return 118;
    case Scenario::kHallway: return 103;
    case Scenario::kTunnel: return 85;
    case Scenario::kLoop: return 318;
    case Scenario::kOutdoor: return 528;
    case Scenario::kRoom: return 14;  // one lap inside the EuRoC Vicon room
  }
  return 0;
}

namespace {

// Route lengths each generator can build (shorter ones would not fit its corridors, racks or turns; the
// room's route must stay inside the room).
std::pair<double, double> length_range_m(Scenario scenario) {
  switch (scenario) {
    case Scenario::kHighbay: return {40, 5000};
    case Scenario::kHallway: return {20, 5000};
    case Scenario::kTunnel: return {20, 5000};
    case Scenario::kLoop: return {160, 5000};
    case Scenario::kOutdoor: return {100, 5000};
    case Scenario::kRoom: return {8, 16.5};
  }
  return {0, 0};
}

}  // namespace

World World::generate(Scenario scenario, std::uint64_t seed, double target_length_m,
                      const std::optional<Eigen::AlignedBox3d>& flight_W) {
  const auto [lo, hi] = length_range_m(scenario);
  if (!(target_length_m == 0 || (target_length_m >= lo && target_length_m <= hi))) {
    throw std::invalid_argument("target length for " + scenario_name(scenario) + " must be 0 (the preset) or within [" +
                                std::to_string(lo) + ", " + std::to_string(hi) + "] m");
  }
  const double length_m = target_length_m > 0 ? target_length_m : preset_length_m(scenario);
  SceneBuilder builder(seed);
  switch (scenario) {
    case Scenario::kHighbay: build_highbay(builder, length_m); break;
    case Scenario::kHallway: build_hallway(builder, length_m); break;
    case Scenario::kTunnel: build_tunnel(builder, length_m); break;
    case Scenario::kLoop: build_loop(builder, length_m); break;
    case Scenario::kOutdoor: build_outdoor(builder, length_m); break;
    case Scenario::kRoom: build_room(builder, length_m, flight_W); break;
  }
  auto impl = std::make_unique<Impl>();
  impl->scenario = scenario;
  impl->scene = builder.finish();
  std::vector<Eigen::AlignedBox3d> boxes;
  for (const auto& shape : impl->scene.shapes) {
    boxes.push_back(shape->bounds());
    impl->bounds.extend(boxes.back());
  }
  impl->bvh.build(boxes);
  return World(std::move(impl));
}

World::World(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
World::~World() = default;
World::World(World&&) noexcept = default;
World& World::operator=(World&&) noexcept = default;

Scenario World::scenario() const { return impl_->scenario; }
const std::vector<Vec3>& World::route_W() const { return impl_->scene.route_W; }
const std::vector<Material>& World::materials() const { return impl_->scene.materials; }
Eigen::AlignedBox3d World::bounds() const { return impl_->bounds; }

std::optional<RayHit> World::raycast(const Vec3& origin_W, const Vec3& dir_W, double max_range_m) const {
  const Ray ray{origin_W, dir_W};
  const auto& shapes = impl_->scene.shapes;
  ShapeHit best;
  int best_shape = -1;
  impl_->bvh.raycast(ray, max_range_m, [&](int i, double t_max) {
    ShapeHit hit;
    if (!shapes[i]->intersect(ray, t_max, &hit)) return t_max;
    best = hit;
    best_shape = i;
    return hit.t;
  });
  if (best_shape < 0) return std::nullopt;
  const Shape& shape = *shapes[best_shape];
  RayHit out;
  out.range_m = best.t;
  out.normal_W = best.normal.dot(dir_W) > 0 ? Vec3(-best.normal) : best.normal;
  out.material = shape.material_at(best.face, best.uv);
  out.uv_m = best.uv + shape.uv_offset;
  out.reflectivity = impl_->scene.materials[out.material].base_grey;
  return out;
}

double World::distance_to_surface(const Vec3& p_W) const {
  const auto& shapes = impl_->scene.shapes;
  return impl_->bvh.nearest(p_W, [&](int i) { return shapes[i]->distance(p_W); });
}

PointCloud World::sample_surfaces(double spacing_m) const {
  if (!(spacing_m > 0)) throw std::invalid_argument("sample_surfaces: spacing must be positive");
  const auto& shapes = impl_->scene.shapes;
  PointCloud cloud;
  std::vector<SurfacePoint> points;
  for (std::size_t s = 0; s < shapes.size(); ++s) {
    points.clear();
    shapes[s]->sample(spacing_m, &points);
    for (const SurfacePoint& sp : points) {
      // Points inside another solid (or on a face it covers) are never seen: leave them out.
      bool hidden = false;
      impl_->bvh.for_each_containing(sp.p, [&](int other) {
        hidden = hidden || (other != static_cast<int>(s) && shapes[other]->contains(sp.p));
      });
      if (hidden) continue;
      cloud.points.push_back(sp.p.cast<float>());
      cloud.intensity.push_back(impl_->scene.materials[shapes[s]->face_material[sp.face]].base_grey);
    }
  }
  return cloud;
}

}  // namespace vilslam::sim
