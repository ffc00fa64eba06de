#include "frontend/frontend_config.h"

#include <yaml-cpp/yaml.h>

#include <functional>
#include <map>

#include "common/error.h"

namespace vilslam {
namespace {

template <typename T>
std::function<void(const YAML::Node&)> setter(T* field) {
  return [field](const YAML::Node& node) { *field = node.as<T>(); };
}

std::map<std::string, std::function<void(const YAML::Node&)>> setters(FrontendConfig* c) {
  return {
      {"min_tracked_matches", setter(&c->min_tracked_matches)},
      {"max_corners", setter(&c->max_corners)},
      {"corner_quality", setter(&c->corner_quality)},
      {"corner_min_distance_px", setter(&c->corner_min_distance_px)},
      {"corner_block_size", setter(&c->corner_block_size)},
      {"corner_subpix_half_window_px", setter(&c->corner_subpix_half_window_px)},
      {"elimination_distance_px", setter(&c->elimination_distance_px)},
      {"klt_window_px", setter(&c->klt_window_px)},
      {"klt_pyramid_levels", setter(&c->klt_pyramid_levels)},
      {"klt_max_iterations", setter(&c->klt_max_iterations)},
      {"klt_epsilon", setter(&c->klt_epsilon)},
      {"klt_max_forward_backward_px", setter(&c->klt_max_forward_backward_px)},
      {"orb_patch_size", setter(&c->orb_patch_size)},
      {"max_descriptor_distance", setter(&c->max_descriptor_distance)},
      {"ratio_test", setter(&c->ratio_test)},
      {"cross_check", setter(&c->cross_check)},
      {"max_epipolar_distance_px", setter(&c->max_epipolar_distance_px)},
      {"min_depth_m", setter(&c->min_depth_m)},
      {"max_depth_m", setter(&c->max_depth_m)},
      {"max_stereo_refinement_px", setter(&c->max_stereo_refinement_px)},
      {"max_stereo_reprojection_px", setter(&c->max_stereo_reprojection_px)},
      {"max_temporal_reprojection_px", setter(&c->max_temporal_reprojection_px)},
      {"pnp_min_points", setter(&c->pnp_min_points)},
      {"pnp_ransac_iterations", setter(&c->pnp_ransac_iterations)},
      {"pnp_ransac_threshold_px", setter(&c->pnp_ransac_threshold_px)},
      {"ransac_seed", setter(&c->ransac_seed)},
  };
}

}  // namespace

void validate_frontend_config(const FrontendConfig& c, const std::string& source) {
  const auto require = [&source](bool ok, const std::string& what) {
    if (!ok) throw InputError(source, "frontend config: " + what);
  };
  require(c.min_tracked_matches >= 0, "min_tracked_matches must be >= 0");
  require(c.max_corners > 0, "max_corners must be > 0");
  require(c.corner_quality > 0 && c.corner_quality < 1, "corner_quality must be in (0, 1)");
  require(c.corner_min_distance_px >= 0, "corner_min_distance_px must be >= 0");
  require(c.corner_block_size >= 3 && c.corner_block_size % 2 == 1, "corner_block_size must be odd and >= 3");
  require(c.corner_subpix_half_window_px >= 0, "corner_subpix_half_window_px must be >= 0");
  require(c.elimination_distance_px >= 0, "elimination_distance_px must be >= 0");
  require(c.klt_window_px >= 5 && c.klt_window_px % 2 == 1, "klt_window_px must be odd and >= 5");
  require(c.klt_pyramid_levels >= 0 && c.klt_pyramid_levels <= 8, "klt_pyramid_levels must be in [0, 8]");
  require(c.klt_max_iterations > 0 && c.klt_epsilon > 0, "klt_max_iterations and klt_epsilon must be > 0");
  require(c.klt_max_forward_backward_px > 0, "klt_max_forward_backward_px must be > 0");
  require(c.orb_patch_size >= 7 && c.orb_patch_size <= 63, "orb_patch_size must be in [7, 63]");
  require(c.max_descriptor_distance > 0 && c.max_descriptor_distance <= 256, "max_descriptor_distance must be in (0, 256]");
  require(c.ratio_test > 0 && c.ratio_test <= 1, "ratio_test must be in (0, 1]");
  require(c.max_epipolar_distance_px > 0, "max_epipolar_distance_px must be > 0");
  require(c.min_depth_m > 0 && c.max_depth_m > c.min_depth_m, "need 0 < min_depth_m < max_depth_m");
  require(c.max_stereo_refinement_px >= 0, "max_stereo_refinement_px must be >= 0");
  require(c.max_stereo_reprojection_px > 0 && c.max_temporal_reprojection_px > 0,
          "reprojection thresholds must be > 0");
  require(c.pnp_min_points >= 4, "pnp_min_points must be >= 4");
  require(c.pnp_ransac_iterations > 0 && c.pnp_ransac_threshold_px > 0,
          "pnp_ransac_iterations and pnp_ransac_threshold_px must be > 0");
}

FrontendConfig load_frontend_config(const std::string& path) {
  YAML::Node root;
  try {
    root = YAML::LoadFile(path);
  } catch (const YAML::BadFile&) {
    throw InputError(path, "cannot open frontend config");
  } catch (const YAML::Exception& e) {
    throw InputError(path, std::string("malformed YAML: ") + e.what(), e.mark.line + 1);
  }
  FrontendConfig config;
  if (root.IsNull()) return config;
  if (!root.IsMap()) throw InputError(path, "frontend config must be a YAML map");
  const auto fields = setters(&config);
  for (const auto& entry : root) {
    const std::string key = entry.first.as<std::string>();
    const auto it = fields.find(key);
    if (it == fields.end()) throw InputError(path, "unknown frontend config key '" + key + "'", entry.first.Mark().line + 1);
    try {
      it->second(entry.second);
    } catch (const YAML::Exception&) {
      throw InputError(path, "bad value for '" + key + "'", entry.second.Mark().line + 1);
    }
  }
  validate_frontend_config(config, path);
  return config;
}

}  // namespace vilslam
