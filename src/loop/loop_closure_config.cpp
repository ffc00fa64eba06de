// The `loop_closure:` section of a run config (loop_closer.h) and its validation.
#include <string>

#include "common/error.h"
#include "loop/loop_closer.h"

namespace vilslam::loop {

YamlFields loop_closure_yaml_fields(LoopClosureConfig& c) {
  KeyFramePolicy& k = c.key_frames;
  DescriptorMatchConfig& d = c.descriptor_matching;
  return {
      yaml_value("enabled", c.enabled),
      yaml_section("key_frames", {yaml_value("min_translation_m", k.min_translation_m),
                                  yaml_value("min_rotation_rad", k.min_rotation_rad),
                                  yaml_value("stop_min_translation_m", k.stop_min_translation_m),
                                  yaml_value("stop_max_speed_mps", k.stop_max_speed_mps),
                                  yaml_value("max_image_scan_gap_s", k.max_image_scan_gap_s),
                                  yaml_value("keep_revisits", k.keep_revisits)}),
      yaml_value("min_time_gap_s", c.min_time_gap_s),
      yaml_value("max_bow_candidates", c.max_bow_candidates),
      yaml_value("min_bow_score", c.min_bow_score),
      yaml_section("descriptor_matching",
                   {yaml_value("max_distance", d.max_distance), yaml_value("ratio_test", d.ratio_test)}),
      yaml_value("min_descriptor_matches", c.min_descriptor_matches),
      yaml_value("min_pnp_inliers", c.min_pnp_inliers),
      yaml_value("pnp_reprojection_px", c.pnp_reprojection_px),
      yaml_value("pnp_ransac_iterations", c.pnp_ransac_iterations),
      yaml_value("pnp_ransac_seed", c.pnp_ransac_seed),
      yaml_value("icp_map_point_spacing_m", c.icp_map_point_spacing_m),
      yaml_value("icp_source_leaf_m", c.icp_source_leaf_m),
      yaml_value("icp_min_plane_spread_ratio", c.icp_min_plane_spread_ratio),
      yaml_value("icp_plane_through_nearest", c.icp_plane_through_nearest),
      yaml_value("icp_num_neighbors", c.icp_num_neighbors),
      yaml_value("icp_loss_scale_m", c.icp_loss_scale_m),
      yaml_value("icp_min_matched_fraction", c.icp_min_matched_fraction),
      yaml_value("icp_min_inlier_fraction", c.icp_min_inlier_fraction),
      yaml_value("icp_max_rms_m", c.icp_max_rms_m),
      yaml_value("icp_min_eigenvalue_per_match", c.icp_min_eigenvalue_per_match),
      yaml_value("icp_max_degenerate_directions", c.icp_max_degenerate_directions),
      yaml_value("fuse_epnp_icp", c.fuse_epnp_icp),
      yaml_value("epnp_sigma_px", c.epnp_sigma_px),
      yaml_value("icp_sigma_m", c.icp_sigma_m),
      yaml_value("max_epnp_icp_translation_m", c.max_epnp_icp_translation_m),
      yaml_value("max_epnp_icp_rotation_rad", c.max_epnp_icp_rotation_rad),
      yaml_value("max_odometry_disagreement_m", c.max_odometry_disagreement_m),
      yaml_value("max_odometry_disagreement_per_m", c.max_odometry_disagreement_per_m),
      yaml_value("loop_sigma_m", c.loop_sigma_m),
      yaml_value("loop_sigma_rad", c.loop_sigma_rad),
      yaml_value("loop_covariance_from_estimates", c.loop_covariance_from_estimates),
      yaml_value("relocalization_loops", c.relocalization_loops),
      yaml_value("relocalization_agreement_m", c.relocalization_agreement_m),
      yaml_value("relocalization_agreement_rad", c.relocalization_agreement_rad),
      yaml_value("resume_window_s", c.resume_window_s), yaml_value("resume_sigma_m", c.resume_sigma_m),
      yaml_value("resume_sigma_rad", c.resume_sigma_rad),
      yaml_value("resume_max_degenerate_directions", c.resume_max_degenerate_directions),
      yaml_value("join_registration", c.join_registration),
  };
}

void validate_loop_closure_config(const LoopClosureConfig& c, const std::string& source) {
  const auto require = [&source](bool ok, const std::string& what) {
    if (!ok) throw InputError(source, "loop_closure." + what);
  };
  const KeyFramePolicy& k = c.key_frames;
  require(k.min_translation_m > 0 && k.min_rotation_rad > 0,
          "key_frames.min_translation_m and min_rotation_rad must be positive");
  require(k.stop_min_translation_m >= 0 && k.stop_max_speed_mps >= 0,
          "key_frames.stop_min_translation_m and stop_max_speed_mps must not be negative");
  require(k.max_image_scan_gap_s >= 0, "key_frames.max_image_scan_gap_s must not be negative");
  require(c.min_time_gap_s >= 0, "min_time_gap_s must not be negative");
  require(c.max_bow_candidates >= 1, "max_bow_candidates must be at least 1");
  require(c.relocalization_loops >= 1, "relocalization_loops must be at least 1");
  require(c.relocalization_agreement_m > 0 && c.relocalization_agreement_rad > 0,
          "relocalization_agreement_m and relocalization_agreement_rad must be positive");
  require(c.resume_window_s >= 0, "resume_window_s must be >= 0");
  require(c.resume_max_degenerate_directions >= 0 && c.resume_max_degenerate_directions <= 6,
          "resume_max_degenerate_directions must be in [0, 6]");
  require(c.resume_sigma_m > 0 && c.resume_sigma_rad > 0, "resume_sigma_m and resume_sigma_rad must be positive");
  require(c.min_bow_score >= 0 && c.min_bow_score <= 1, "min_bow_score must be in [0, 1]");
  require(c.descriptor_matching.max_distance >= 0 && c.descriptor_matching.max_distance <= 256,
          "descriptor_matching.max_distance must be in [0, 256]");
  require(c.descriptor_matching.ratio_test > 0 && c.descriptor_matching.ratio_test <= 1,
          "descriptor_matching.ratio_test must be in (0, 1]");
  // EPnP's minimal set is 4 points, OpenCV's EPnP RANSAC kernel samples 5.
  require(c.min_descriptor_matches >= 5 && c.min_pnp_inliers >= 5,
          "min_descriptor_matches and min_pnp_inliers must be at least 5");
  require(c.pnp_reprojection_px > 0, "pnp_reprojection_px must be positive");
  require(c.pnp_ransac_iterations >= 1, "pnp_ransac_iterations must be at least 1");
  require(c.icp_min_matched_fraction >= 0 && c.icp_min_matched_fraction <= 1 && c.icp_min_inlier_fraction >= 0 &&
              c.icp_min_inlier_fraction <= 1,
          "icp_min_matched_fraction and icp_min_inlier_fraction must be in [0, 1]");
  require(c.icp_max_rms_m > 0, "icp_max_rms_m must be positive");
  require(c.epnp_sigma_px > 0 && c.icp_sigma_m > 0, "epnp_sigma_px and icp_sigma_m must be positive");
  require(c.icp_map_point_spacing_m > 0 && c.icp_source_leaf_m > 0,
          "icp_map_point_spacing_m and icp_source_leaf_m must be positive");
  require(c.icp_min_plane_spread_ratio >= 0 && c.icp_min_plane_spread_ratio <= 1,
          "icp_min_plane_spread_ratio must be in [0, 1]");
  require(c.icp_loss_scale_m > 0, "icp_loss_scale_m must be positive");
  require(c.icp_num_neighbors >= 3, "icp_num_neighbors must be at least 3");
  require(c.icp_min_eigenvalue_per_match >= 0, "icp_min_eigenvalue_per_match must not be negative");
  require(c.icp_max_degenerate_directions >= 0 && c.icp_max_degenerate_directions <= 6,
          "icp_max_degenerate_directions must be in [0, 6]");
  require(c.max_epnp_icp_translation_m > 0 && c.max_epnp_icp_rotation_rad > 0,
          "max_epnp_icp_translation_m and max_epnp_icp_rotation_rad must be positive");
  require(c.max_odometry_disagreement_m > 0 && c.max_odometry_disagreement_per_m >= 0,
          "max_odometry_disagreement_m must be positive and max_odometry_disagreement_per_m not negative");
  require(c.loop_sigma_m > 0 && c.loop_sigma_rad > 0, "loop_sigma_m and loop_sigma_rad must be positive");
}

}  // namespace vilslam::loop
