#include <gtest/gtest.h>

#include <fstream>
#include <vector>

#include "common/error.h"
#include "frontend/frontend_config.h"
#include "test_util.h"

namespace vilslam {
namespace {

// Every field, in declaration order, as numbers (to compare whole configs).
std::vector<double> as_numbers(const FrontendConfig& c) {
  return {double(c.min_tracked_matches), double(c.max_corners), c.corner_quality, c.corner_min_distance_px,
          double(c.corner_block_size), double(c.corner_subpix_half_window_px), c.elimination_distance_px,
          double(c.klt_window_px), double(c.klt_pyramid_levels), double(c.klt_max_iterations), c.klt_epsilon,
          c.klt_max_forward_backward_px, double(c.orb_patch_size), double(c.max_descriptor_distance), c.ratio_test,
          double(c.cross_check), c.max_epipolar_distance_px, c.min_depth_m, c.max_depth_m,
          c.max_stereo_refinement_px, c.max_stereo_reprojection_px, c.max_temporal_reprojection_px,
          double(c.pnp_min_points), double(c.pnp_ransac_iterations), c.pnp_ransac_threshold_px,
          double(c.ransac_seed)};
}

std::string write_yaml(const std::string& text) {
  const std::string path = (test::temp_dir() / "frontend.yaml").string();
  std::ofstream(path) << text;
  return path;
}

TEST(FrontendConfig, ShippedYamlHoldsTheDefaults) {
  EXPECT_EQ(as_numbers(load_frontend_config(std::string(VILSLAM_SOURCE_DIR) + "/config/frontend.yaml")),
            as_numbers(FrontendConfig{}));
}

TEST(FrontendConfig, ReadsGivenKeysOverDefaults) {
  const FrontendConfig c = load_frontend_config(write_yaml("max_corners: 123\nratio_test: 0.6\ncross_check: false\n"));
  EXPECT_EQ(c.max_corners, 123);
  EXPECT_EQ(c.ratio_test, 0.6);
  EXPECT_FALSE(c.cross_check);
  EXPECT_EQ(c.klt_window_px, FrontendConfig{}.klt_window_px);
}

TEST(FrontendConfig, BadFilesThrowInputError) {
  EXPECT_THROW(load_frontend_config("/nonexistent/frontend.yaml"), InputError);
  EXPECT_THROW(load_frontend_config(write_yaml("max_cornerz: 5\n")), InputError);
  EXPECT_THROW(load_frontend_config(write_yaml("max_corners: many\n")), InputError);
  EXPECT_THROW(load_frontend_config(write_yaml("max_corners: [1, 2\n")), InputError);
  EXPECT_THROW(load_frontend_config(write_yaml("klt_window_px: 20\n")), InputError);
  EXPECT_THROW(load_frontend_config(write_yaml("min_depth_m: 5\nmax_depth_m: 2\n")), InputError);
  EXPECT_THROW(load_frontend_config(write_yaml("- 1\n- 2\n")), InputError);
}

}  // namespace
}  // namespace vilslam
