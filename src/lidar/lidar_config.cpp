#include "lidar/lidar_config.h"

#include <yaml-cpp/yaml.h>

#include <filesystem>
#include <functional>
#include <map>

#include "common/error.h"

namespace vilslam::lidar {

namespace {

using Setter = std::function<void(const YAML::Node&)>;

template <typename T>
Setter set(T& field) {
  return [&field](const YAML::Node& node) { field = node.as<T>(); };
}

Setter set_loss(RobustLoss& loss) {
  return [&loss](const YAML::Node& node) {
    const std::string name = node.as<std::string>();
    if (name != "huber" && name != "cauchy") throw YAML::Exception(node.Mark(), "loss must be huber or cauchy");
    loss = name == "huber" ? RobustLoss::kHuber : RobustLoss::kCauchy;
  };
}

std::map<std::string, Setter> voxel_keys(VoxelMapConfig& c) {
  return {{"voxel_size_m", set(c.voxel_size_m)},
          {"min_point_spacing_m", set(c.min_point_spacing_m)},
          {"max_points_per_voxel", set(c.max_points_per_voxel)},
          {"max_distance_m", set(c.max_distance_m)}};
}

// Applies a YAML mapping to fields by name; unknown keys are errors so that typos do not pass silently.
void apply(const std::string& path, const YAML::Node& node, const std::string& section,
           const std::map<std::string, Setter>& keys) {
  if (!node) return;
  if (!node.IsMap()) throw InputError(path, "section '" + section + "' must be a mapping", node.Mark().line + 1);
  for (const auto& entry : node) {
    const std::string key = entry.first.as<std::string>();
    const auto it = keys.find(key);
    if (it == keys.end()) throw InputError(path, "unknown key '" + section + "." + key + "'", entry.first.Mark().line + 1);
    it->second(entry.second);
  }
}

}  // namespace

LidarConfig load_lidar_config(const std::string& path) {
  if (!std::filesystem::is_regular_file(path)) throw InputError(path, "file does not exist");
  LidarConfig c;
  try {
    const YAML::Node root = YAML::LoadFile(path);
    RingConfig& r = c.rings;
    apply(path, root["rings"], "rings",
          {{"num_rings", set(r.num_rings)}, {"min_elevation_deg", set(r.min_elevation_deg)},
           {"max_elevation_deg", set(r.max_elevation_deg)}, {"min_range_m", set(r.min_range_m)},
           {"max_range_m", set(r.max_range_m)}});
    FeatureConfig& f = c.features;
    apply(path, root["features"], "features",
          {{"half_window", set(f.half_window)}, {"sectors_per_ring", set(f.sectors_per_ring)},
           {"max_edges_per_sector", set(f.max_edges_per_sector)},
           {"max_surfaces_per_sector", set(f.max_surfaces_per_sector)},
           {"edge_min_smoothness", set(f.edge_min_smoothness)},
           {"surface_max_smoothness", set(f.surface_max_smoothness)},
           {"occlusion_jump_ratio", set(f.occlusion_jump_ratio)},
           {"max_neighbor_gap_ratio", set(f.max_neighbor_gap_ratio)}});
    if (root["map"]) {
      apply(path, root["map"]["edges"], "map.edges", voxel_keys(c.map.edges));
      apply(path, root["map"]["surfaces"], "map.surfaces", voxel_keys(c.map.surfaces));
    }
    RegistrationConfig& g = c.registration;
    AssociationConfig& a = g.association;
    apply(path, root["registration"], "registration",
          {{"max_outer_iterations", set(g.max_outer_iterations)},
           {"max_inner_iterations", set(g.max_inner_iterations)},
           {"converged_translation_m", set(g.converged_translation_m)},
           {"converged_rotation_rad", set(g.converged_rotation_rad)},
           {"loss", set_loss(g.loss)}, {"loss_scale_m", set(g.loss_scale_m)},
           {"source_edge_leaf_m", set(g.source_edge_leaf_m)},
           {"source_surface_leaf_m", set(g.source_surface_leaf_m)},
           {"degenerate_min_eigenvalue_per_match", set(g.degenerate_min_eigenvalue_per_match)},
           {"remap_degenerate_directions", set(g.remap_degenerate_directions)},
           {"num_neighbors", set(a.num_neighbors)},
           {"max_neighbor_distance_m", set(a.max_neighbor_distance_m)},
           {"min_line_eigen_ratio", set(a.min_line_eigen_ratio)},
           {"max_plane_point_distance_m", set(a.max_plane_point_distance_m)}});
  } catch (const YAML::Exception& e) {
    throw InputError(path, e.msg, e.mark.line + 1);
  }
  if (c.rings.num_rings < 1 || c.features.half_window < 1 || c.features.sectors_per_ring < 1 ||
      c.map.edges.voxel_size_m <= 0.0 || c.map.surfaces.voxel_size_m <= 0.0) {
    throw InputError(path, "num_rings, half_window, sectors_per_ring and voxel sizes must be positive");
  }
  return c;
}

}  // namespace vilslam::lidar
