#include "frontend/frontend_config.h"

#include "common/error.h"

namespace vilslam {

YamlFields frontend_yaml_fields(FrontendConfig& c) {
  return {
      yaml_value("clahe_clip_limit", c.clahe_clip_limit),
      yaml_value("clahe_tiles", c.clahe_tiles),
      yaml_value("vignetting_samples", c.vignetting_samples),
      yaml_value("min_tracked_matches", c.min_tracked_matches),
      yaml_value("max_corners", c.max_corners),
      yaml_value("corner_quality", c.corner_quality),
      yaml_value("corner_min_distance_px", c.corner_min_distance_px),
      yaml_value("corner_block_size", c.corner_block_size),
      yaml_value("corner_subpix_half_window_px", c.corner_subpix_half_window_px),
      yaml_value("elimination_distance_px", c.elimination_distance_px),
      yaml_value("klt_window_px", c.klt_window_px),
      yaml_value("klt_pyramid_levels", c.klt_pyramid_levels),
      yaml_value("klt_max_iterations", c.klt_max_iterations),
      yaml_value("klt_epsilon", c.klt_epsilon),
      yaml_value("klt_max_forward_backward_px", c.klt_max_forward_backward_px),
      yaml_value("klt_final_window_px", c.klt_final_window_px),
      yaml_value("orb_patch_size", c.orb_patch_size),
      yaml_value("max_descriptor_distance", c.max_descriptor_distance),
      yaml_value("ratio_test", c.ratio_test),
      yaml_value("cross_check", c.cross_check),
      yaml_value("max_epipolar_distance_px", c.max_epipolar_distance_px),
      yaml_value("min_depth_m", c.min_depth_m),
      yaml_value("max_depth_m", c.max_depth_m),
      yaml_value("max_stereo_refinement_px", c.max_stereo_refinement_px),
      yaml_value("max_stereo_reprojection_px", c.max_stereo_reprojection_px),
      yaml_value("max_temporal_reprojection_px", c.max_temporal_reprojection_px),
      yaml_value("pnp_min_points", c.pnp_min_points),
      yaml_value("pnp_ransac_iterations", c.pnp_ransac_iterations),
      yaml_value("pnp_ransac_threshold_px", c.pnp_ransac_threshold_px),
      yaml_value("ransac_seed", c.ransac_seed),
  };
}

void validate_frontend_config(const FrontendConfig& c, const std::string& source) {
  const auto require = [&source](bool ok, const std::string& what) {
    if (!ok) throw InputError(source, "frontend config: " + what);
  };
  require(c.clahe_clip_limit >= 0, "clahe_clip_limit must be >= 0 (0 = off)");
  require(c.clahe_tiles >= 1 && c.clahe_tiles <= 64, "clahe_tiles must be in [1, 64]");
  require(c.vignetting_samples >= 0, "vignetting_samples must be >= 0 (0 = off)");
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
  require(c.klt_final_window_px == 0 ||
              (c.klt_final_window_px >= 5 && c.klt_final_window_px % 2 == 1 && c.klt_final_window_px <= c.klt_window_px),
          "klt_final_window_px must be 0 (off) or odd, >= 5 and at most klt_window_px");
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

}  // namespace vilslam
