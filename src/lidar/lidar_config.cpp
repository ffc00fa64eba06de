#include "lidar/lidar_config.h"

#include <algorithm>
#include <iterator>

#include "common/error.h"

namespace vilslam::lidar {

namespace {

YamlField loss_field(RobustLoss& loss) {
  YamlField f;
  f.key = "loss";
  f.read = [&loss](const YAML::Node& node, const std::string& file, const std::string& key_path) {
    const std::string name = node.as<std::string>();
    if (name != "huber" && name != "cauchy") {
      throw InputError(file, "'" + key_path + "' must be huber or cauchy", node.Mark().line + 1);
    }
    loss = name == "huber" ? RobustLoss::kHuber : RobustLoss::kCauchy;
  };
  f.write = [&loss]() { return YAML::Node(loss == RobustLoss::kHuber ? "huber" : "cauchy"); };
  return f;
}

YamlField method_field(FeatureMethod& method) {
  static const char* const kNames[] = {"auto", "rings", "neighbourhood"};
  YamlField f;
  f.key = "method";
  f.read = [&method](const YAML::Node& node, const std::string& file, const std::string& key_path) {
    const std::string name = node.as<std::string>();
    const auto* it = std::find(std::begin(kNames), std::end(kNames), name);
    if (it == std::end(kNames)) {
      throw InputError(file, "'" + key_path + "' must be auto, rings or neighbourhood", node.Mark().line + 1);
    }
    method = static_cast<FeatureMethod>(it - std::begin(kNames));
  };
  f.write = [&method]() { return YAML::Node(kNames[static_cast<int>(method)]); };
  return f;
}

YamlFields neighbourhood_fields(NeighbourhoodFeatureConfig& c) {
  return {yaml_value("num_neighbours", c.num_neighbours), yaml_value("candidate_stride", c.candidate_stride),
          yaml_value("max_radius_per_range", c.max_radius_per_range),
          yaml_value("surface_max_noise_sigmas", c.surface_max_noise_sigmas),
          yaml_value("min_surface_spread_ratio", c.min_surface_spread_ratio),
          yaml_value("edge_min_noise_sigmas", c.edge_min_noise_sigmas),
          yaml_value("edge_min_curvature", c.edge_min_curvature), yaml_value("azimuth_cells", c.azimuth_cells),
          yaml_value("elevation_cells", c.elevation_cells), yaml_value("max_edges_per_cell", c.max_edges_per_cell),
          yaml_value("max_surfaces_per_cell", c.max_surfaces_per_cell)};
}

YamlFields voxel_fields(VoxelMapConfig& c) {
  return {yaml_value("voxel_size_m", c.voxel_size_m), yaml_value("min_point_spacing_m", c.min_point_spacing_m),
          yaml_value("max_points_per_voxel", c.max_points_per_voxel), yaml_value("max_distance_m", c.max_distance_m)};
}

}  // namespace

YamlFields lidar_yaml_fields(LidarConfig& c) {
  RingConfig& r = c.rings;
  FeatureConfig& f = c.features;
  RegistrationConfig& g = c.registration;
  AssociationConfig& a = g.association;
  return {
      yaml_section("rings", {yaml_value("num_rings", r.num_rings), yaml_value("min_elevation_deg", r.min_elevation_deg),
                             yaml_value("max_elevation_deg", r.max_elevation_deg),
                             yaml_value("min_range_m", r.min_range_m), yaml_value("max_range_m", r.max_range_m)}),
      yaml_section("features", {method_field(f.method), yaml_value("reference_rings", f.reference_rings),
                                yaml_value("half_window", f.half_window),
                                yaml_value("sectors_per_ring", f.sectors_per_ring),
                                yaml_value("max_edges_per_sector", f.max_edges_per_sector),
                                yaml_value("max_surfaces_per_sector", f.max_surfaces_per_sector),
                                yaml_value("edge_min_smoothness", f.edge_min_smoothness),
                                yaml_value("range_noise_sigma_m", f.range_noise_sigma_m),
                                yaml_value("beam_divergence_rad", f.beam_divergence_rad),
                                yaml_value("edge_noise_sigmas", f.edge_noise_sigmas),
                                yaml_value("surface_max_smoothness", f.surface_max_smoothness),
                                yaml_value("occlusion_jump_ratio", f.occlusion_jump_ratio),
                                yaml_value("max_neighbor_gap_ratio", f.max_neighbor_gap_ratio),
                                yaml_section("neighbourhood", neighbourhood_fields(f.neighbourhood))}),
      yaml_section("map", {yaml_section("edges", voxel_fields(c.map.edges)),
                           yaml_section("surfaces", voxel_fields(c.map.surfaces))}),
      yaml_section("registration",
                   {yaml_value("max_outer_iterations", g.max_outer_iterations),
                    yaml_value("max_inner_iterations", g.max_inner_iterations),
                    yaml_value("converged_translation_m", g.converged_translation_m),
                    yaml_value("converged_rotation_rad", g.converged_rotation_rad), loss_field(g.loss),
                    yaml_value("loss_scale_m", g.loss_scale_m), yaml_value("source_edge_leaf_m", g.source_edge_leaf_m),
                    yaml_value("source_surface_leaf_m", g.source_surface_leaf_m),
                    yaml_value("degenerate_min_eigenvalue_per_match", g.degenerate_min_eigenvalue_per_match),
                    yaml_value("remap_degenerate_directions", g.remap_degenerate_directions),
                    yaml_value("tilt_prior_sigma_rad", g.tilt_prior_sigma_rad),
                    yaml_value("num_neighbors", a.num_neighbors),
                    yaml_value("max_neighbor_distance_m", a.max_neighbor_distance_m),
                    yaml_value("min_line_eigen_ratio", a.min_line_eigen_ratio),
                    yaml_value("max_plane_point_distance_m", a.max_plane_point_distance_m),
                    yaml_value("max_normal_angle_deg", a.max_normal_angle_deg)}),
  };
}

FeatureConfig features_for_registration(const LidarConfig& c) {
  FeatureConfig features = c.features;
  features.ring_normals = c.registration.association.max_normal_angle_deg > 0.0;
  return features;
}

void validate_lidar_config(const LidarConfig& c, const std::string& source) {
  if (!(c.registration.tilt_prior_sigma_rad >= 0.0)) {
    throw InputError(source, "registration.tilt_prior_sigma_rad must be >= 0 (0 = off)");
  }
  const double normal_angle_deg = c.registration.association.max_normal_angle_deg;
  if (!(normal_angle_deg >= 0.0 && normal_angle_deg < 90.0)) {
    throw InputError(source, "registration.max_normal_angle_deg must be in [0, 90) (0 = off)");
  }
  if (!(c.features.beam_divergence_rad >= 0.0)) {
    throw InputError(source, "features.beam_divergence_rad must be >= 0 (0 = off)");
  }
  if (c.rings.num_rings < 1 || c.features.half_window < 1 || c.features.sectors_per_ring < 1 ||
      c.map.edges.voxel_size_m <= 0.0 || c.map.surfaces.voxel_size_m <= 0.0) {
    throw InputError(source, "rings.num_rings, features.half_window, features.sectors_per_ring and map voxel_size_m "
                             "must be positive");
  }
  const NeighbourhoodFeatureConfig& n = c.features.neighbourhood;
  if (c.features.reference_rings < 1 || n.num_neighbours < 4 || n.candidate_stride < 1 || n.azimuth_cells < 1 || n.elevation_cells < 1 ||
      n.max_edges_per_cell < 0 || n.max_surfaces_per_cell < 0 || !(n.max_radius_per_range > 0.0)) {
    throw InputError(source, "features.reference_rings and the neighbourhood counts, cells and radius must be "
                             "positive (num_neighbours at least 4)");
  }
}

LidarConfig load_lidar_config(const std::string& path) {
  LidarConfig c;
  read_yaml_fields(load_yaml_file(path), path, "", lidar_yaml_fields(c));
  validate_lidar_config(c, path);
  return c;
}

}  // namespace vilslam::lidar
