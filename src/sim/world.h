#pragma once
// A simulated world: textured geometry that cameras and the LiDAR see by ray casting, a route to fly
// through it, and a dense sampling of its surfaces (the reference model, like the paper's Faro scan).
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "common/lie.h"
#include "io/cloud_io.h"

namespace vilslam::sim {

enum class Scenario { kHighbay, kHallway, kTunnel, kLoop, kOutdoor, kRoom };

// "highbay" | "hallway" | "tunnel" | "loop" | "outdoor" | "room"; throws std::invalid_argument otherwise.
Scenario parse_scenario(const std::string& name);
std::string scenario_name(Scenario scenario);
// The paper's path length of each preset (highbay 118 m, hallway 103, tunnel 85, loop 318, outdoor 528).
double preset_length_m(Scenario scenario);

struct RayHit {
  double range_m = 0;          // distance along the (unit) ray
  Vec3 normal_W;               // unit surface normal facing the ray origin
  int material = 0;            // index into World::materials()
  Eigen::Vector2d uv_m;        // surface coordinates in metres, continuous across a face
  float reflectivity = 0.5f;   // 0..1, drives LiDAR intensity
};

// What a surface looks like: the camera renderer turns it into texture content.
struct Material {
  enum class Kind { kPlain, kConcrete, kClutter, kPoster, kFoliage, kGround } kind = Kind::kPlain;
  float base_grey = 0.5f;      // mean albedo 0..1
  float contrast = 0.1f;       // amplitude of the texture content
  std::uint64_t seed = 0;
};

class World {
 public:
  // Builds the scenario from the seed. target_length_m > 0 sizes the route (and the world around it)
  // to about that length; 0 uses the preset length. Throws std::invalid_argument for a length the
  // scenario cannot be built at (highbay >= 40 m, hallway and tunnel >= 20, loop >= 160, outdoor >= 100,
  // room 8..16.5, all <= 5000). flight_W (room only): bounds of a recorded flight's positions that the
  // room must hold with a margin.
  static World generate(Scenario scenario, std::uint64_t seed, double target_length_m = 0,
                        const std::optional<Eigen::AlignedBox3d>& flight_W = std::nullopt);
  ~World();
  World(World&&) noexcept;
  World& operator=(World&&) noexcept;

  Scenario scenario() const;
  // Nearest hit of the ray origin + s * dir_W (dir_W unit), s in (0, max_range_m]; thread-safe.
  std::optional<RayHit> raycast(const Vec3& origin_W, const Vec3& dir_W, double max_range_m) const;
  // Closed route through free space at sensor height: waypoints in order, first == last.
  const std::vector<Vec3>& route_W() const;
  const std::vector<Material>& materials() const;
  // Points on every surface, about spacing_m apart (the reference model).
  PointCloud sample_surfaces(double spacing_m) const;
  // Unsigned distance from a point to the nearest surface (for consistency tests).
  double distance_to_surface(const Vec3& p_W) const;
  // Axis-aligned bounds of the geometry.
  Eigen::AlignedBox3d bounds() const;

 private:
  struct Impl;
  explicit World(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace vilslam::sim
