#include <gtest/gtest.h>

#include <vector>

#include "common/error.h"
#include "frontend/frontend_config.h"

namespace vilslam {
namespace {

// Every field, in declaration order, as numbers (to compare whole configs).
std::vector<double> as_numbers(const FrontendConfig& c) {
  return {c.clahe_clip_limit, double(c.clahe_tiles), double(c.vignetting_samples), double(c.min_tracked_matches),
          double(c.max_corners), c.corner_quality, c.corner_min_distance_px,
          double(c.corner_block_size), double(c.corner_subpix_half_window_px), c.elimination_distance_px,
          double(c.klt_window_px), double(c.klt_pyramid_levels), double(c.klt_max_iterations), c.klt_epsilon,
          c.klt_max_forward_backward_px, double(c.klt_final_window_px), double(c.orb_patch_size), double(c.max_descriptor_distance), c.ratio_test,
          double(c.cross_check), c.max_epipolar_distance_px, c.min_depth_m, c.max_depth_m,
          c.max_stereo_refinement_px, c.max_stereo_reprojection_px, c.max_temporal_reprojection_px,
          double(c.pnp_min_points), double(c.pnp_ransac_iterations), c.pnp_ransac_threshold_px,
          double(c.ransac_seed)};
}

FrontendConfig read(const std::string& text) {
  FrontendConfig c;
  read_yaml_fields(YAML::Load(text), "frontend.yaml", "", frontend_yaml_fields(c));
  validate_frontend_config(c, "frontend.yaml");
  return c;
}

TEST(FrontendConfig, ReadsEveryKey) {
  // config/run_default.yaml (tests/pipeline) checks the keys against the defaults; here every key
  // gets a value other than its default.
  const FrontendConfig c = read(
      "clahe_clip_limit: 2.5\nclahe_tiles: 6\nvignetting_samples: 3000\n"
      "min_tracked_matches: 100\nmax_corners: 123\ncorner_quality: 0.01\ncorner_min_distance_px: 6\n"
      "corner_block_size: 5\ncorner_subpix_half_window_px: 2\nelimination_distance_px: 5\nklt_window_px: 15\n"
      "klt_pyramid_levels: 2\nklt_max_iterations: 20\nklt_epsilon: 0.02\nklt_max_forward_backward_px: 0.5\n"
      "klt_final_window_px: 9\n"
      "orb_patch_size: 25\nmax_descriptor_distance: 50\nratio_test: 0.6\ncross_check: false\n"
      "max_epipolar_distance_px: 1.5\nmin_depth_m: 0.5\nmax_depth_m: 30\nmax_stereo_refinement_px: 2\n"
      "max_stereo_reprojection_px: 1.0\nmax_temporal_reprojection_px: 2.5\npnp_min_points: 8\n"
      "pnp_ransac_iterations: 50\npnp_ransac_threshold_px: 1.5\nransac_seed: 7\n");
  EXPECT_EQ(as_numbers(c), (std::vector<double>{2.5, 6, 3000, 100, 123, 0.01, 6, 5, 2, 5, 15, 2, 20, 0.02, 0.5, 9,
                                                 25, 50, 0.6, 0, 1.5, 0.5, 30, 2, 1.0, 2.5, 8, 50, 1.5, 7}));
  FrontendConfig defaults;
  EXPECT_EQ(frontend_yaml_fields(defaults).size(), as_numbers(c).size());
}

TEST(FrontendConfig, ReadsGivenKeysOverDefaults) {
  const FrontendConfig c = read("max_corners: 123\nratio_test: 0.6\ncross_check: false\n");
  EXPECT_EQ(c.max_corners, 123);
  EXPECT_EQ(c.ratio_test, 0.6);
  EXPECT_FALSE(c.cross_check);
  EXPECT_EQ(c.klt_window_px, FrontendConfig{}.klt_window_px);
}

TEST(FrontendConfig, BadValuesThrowInputError) {
  EXPECT_THROW(read("max_cornerz: 5\n"), InputError);
  EXPECT_THROW(read("max_corners: many\n"), InputError);
  EXPECT_THROW(read("ratio_test: .nan\n"), InputError);
  EXPECT_THROW(read("klt_window_px: 20\n"), InputError);
  EXPECT_THROW(read("min_depth_m: 5\nmax_depth_m: 2\n"), InputError);
  EXPECT_THROW(read("clahe_clip_limit: -1\n"), InputError);
  EXPECT_THROW(read("clahe_tiles: 0\n"), InputError);
  EXPECT_THROW(read("vignetting_samples: -5\n"), InputError);
  EXPECT_THROW(read("klt_final_window_px: 10\n"), InputError);             // even
  EXPECT_THROW(read("klt_window_px: 15\nklt_final_window_px: 17\n"), InputError);  // above the window
  EXPECT_THROW(read("- 1\n- 2\n"), InputError);
}

}  // namespace
}  // namespace vilslam
