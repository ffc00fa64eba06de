// The `loop_closure:` YAML section: every key round-trips, unknown keys and bad values are InputErrors.
#include <gtest/gtest.h>

#include <string>

#include "common/error.h"
#include "loop/loop_closer.h"

namespace vilslam::loop {
namespace {

LoopClosureConfig read(const std::string& yaml) {
  LoopClosureConfig c;
  read_yaml_fields(YAML::Load(yaml), "run.yaml", "loop_closure", loop_closure_yaml_fields(c));
  validate_loop_closure_config(c, "run.yaml");
  return c;
}

TEST(LoopClosureConfig, DefaultsAreValidAndEveryFieldRoundTrips) {
  LoopClosureConfig c;
  EXPECT_NO_THROW(validate_loop_closure_config(c, "defaults"));
  c.enabled = false;
  c.key_frames.min_translation_m = 2.5;
  c.key_frames.min_rotation_rad = 0.1;
  c.key_frames.max_image_scan_gap_s = 0.01;
  c.min_time_gap_s = 12.5;
  c.max_bow_candidates = 5;
  c.min_bow_score = 0.05;
  c.descriptor_matching.max_distance = 50;
  c.descriptor_matching.ratio_test = 0.8;
  c.min_descriptor_matches = 30;
  c.min_pnp_inliers = 20;
  c.pnp_reprojection_px = 2.5;
  c.pnp_ransac_iterations = 300;
  c.pnp_ransac_seed = 7;
  c.icp_map_point_spacing_m = 0.08;
  c.icp_source_leaf_m = 0.15;
  c.icp_min_matched_fraction = 0.45;
  c.icp_min_inlier_fraction = 0.6;
  c.icp_max_rms_m = 0.08;
  c.icp_min_eigenvalue_per_match = 0.02;
  c.icp_max_degenerate_directions = 0;
  c.icp_min_plane_spread_ratio = 0.2;
  c.icp_plane_through_nearest = false;
  c.icp_num_neighbors = 8;
  c.icp_loss_scale_m = 0.07;
  c.max_epnp_icp_translation_m = 0.25;
  c.max_epnp_icp_rotation_rad = 0.04;
  c.max_odometry_disagreement_m = 1.5;
  c.max_odometry_disagreement_per_m = 0.03;
  c.loop_sigma_m = 0.05;
  c.loop_sigma_rad = 0.005;
  c.loop_covariance_from_estimates = false;
  const std::string text = YAML::Dump(write_yaml_fields(loop_closure_yaml_fields(c)));
  LoopClosureConfig back = read(text);
  EXPECT_EQ(YAML::Dump(write_yaml_fields(loop_closure_yaml_fields(back))), text);
  EXPECT_FALSE(back.enabled);
  EXPECT_EQ(back.key_frames.max_image_scan_gap_s, 0.01);
  EXPECT_EQ(back.descriptor_matching.ratio_test, 0.8);
  EXPECT_EQ(back.pnp_ransac_seed, 7u);
  EXPECT_EQ(back.loop_sigma_rad, 0.005);
  EXPECT_FALSE(back.loop_covariance_from_estimates);
  EXPECT_EQ(back.icp_max_degenerate_directions, 0);
  EXPECT_EQ(back.icp_loss_scale_m, 0.07);
  EXPECT_FALSE(back.icp_plane_through_nearest);
  EXPECT_EQ(back.icp_num_neighbors, 8);
}

TEST(LoopClosureConfig, KeysOverrideDefaults) {
  const LoopClosureConfig c = read("min_time_gap_s: 20\nkey_frames: {min_translation_m: 0.5}\nicp_num_neighbors: 9\n");
  EXPECT_EQ(c.min_time_gap_s, 20.0);
  EXPECT_EQ(c.key_frames.min_translation_m, 0.5);
  EXPECT_EQ(c.key_frames.min_rotation_rad, LoopClosureConfig{}.key_frames.min_rotation_rad);
  EXPECT_EQ(c.icp_num_neighbors, 9);
}

TEST(LoopClosureConfig, BadValuesAndUnknownKeysAreInputErrors) {
  for (const std::string yaml : {"min_time_gap_s: -1",
                                 "max_bow_candidates: 0",
                                 "min_bow_score: 1.5",
                                 "min_pnp_inliers: 4",
                                 "min_descriptor_matches: 2",
                                 "pnp_reprojection_px: 0",
                                 "pnp_ransac_iterations: 0",
                                 "icp_min_inlier_fraction: 1.2",
                                 "icp_min_matched_fraction: -0.1",
                                 "icp_max_rms_m: 0",
                                 "icp_map_point_spacing_m: 0",
                                 "icp_source_leaf_m: -1",
                                 "icp_max_degenerate_directions: 7",
                                 "icp_min_plane_spread_ratio: 1.5",
                                 "icp_loss_scale_m: 0",
                                 "icp_num_neighbors: 2",
                                 "max_epnp_icp_translation_m: 0",
                                 "max_odometry_disagreement_m: 0",
                                 "loop_sigma_m: 0",
                                 "loop_sigma_rad: -1",
                                 "key_frames: {min_translation_m: 0}",
                                 "descriptor_matching: {ratio_test: 0}",
                                 "descriptor_matching: {max_distance: 300}",
                                 "min_time_gap: 30",
                                 "key_frames: {min_rotation_deg: 10}",
                                 "min_time_gap_s: thirty",
                                 "loop_sigma_m: .nan",
                                 "enabled: maybe"}) {
    EXPECT_THROW(read(yaml), InputError) << yaml;
  }
}

TEST(LoopClosureConfig, ErrorsNameTheKeyPath) {
  try {
    read("key_frames: {min_rotation_deg: 10}");
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("loop_closure.key_frames.min_rotation_deg"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace vilslam::loop
