// The run config: config/run_default.yaml is exactly the defaults, every section reaches its module, the
// written config reads back, and bad files are InputErrors naming the file and the key.
#include <gtest/gtest.h>

#include <fstream>

#include "common/error.h"
#include "pipeline/run_config.h"
#include "test_util.h"

namespace vilslam {
namespace {

const std::string kConfigDir = std::string(VILSLAM_SOURCE_DIR) + "/config/";

std::string write_file(const std::string& text) {
  const std::string path = (test::temp_dir() / "run.yaml").string();
  std::ofstream(path) << text;
  return path;
}

TEST(RunConfig, DefaultFileListsEveryKeyAtItsDefault) {
  const std::string path = kConfigDir + "run_default.yaml";
  const std::string defaults = run_config_yaml(OfflineRunConfig{});
  EXPECT_EQ(run_config_yaml(load_run_config(path)), defaults);
  EXPECT_EQ(test::yaml_key_paths(YAML::LoadFile(path)), test::yaml_key_paths(YAML::Load(defaults)));
}

TEST(RunConfig, ShippedRigConfigsLoad) {
  const OfflineRunConfig c = load_run_config(kConfigDir + "run_vlp16.yaml");
  EXPECT_EQ(c.lidar.lidar.rings.num_rings, 16);
  EXPECT_TRUE(c.lidar.dewarp);
  EXPECT_TRUE(c.lidar.lidar.registration.remap_degenerate_directions);
  const OfflineRunConfig hesai = load_run_config(kConfigDir + "run_hesai128.yaml");
  EXPECT_EQ(hesai.lidar.lidar.features.method, lidar::FeatureMethod::kRings);
  EXPECT_EQ(hesai.lidar.lidar.registration.tilt_prior_sigma_rad, 0.0);
  const OfflineRunConfig mid360 = load_run_config(kConfigDir + "run_mid360.yaml");
  EXPECT_EQ(mid360.lidar.lidar.features.method, lidar::FeatureMethod::kNeighbourhood);
  EXPECT_EQ(mid360.lidar.lidar.rings.max_range_m, 70.0);
  EXPECT_EQ(mid360.lidar.lidar.registration.association.max_plane_point_distance_m, 0.05);
  EXPECT_EQ(mid360.lidar.lidar.registration.tilt_prior_sigma_rad, 0.0);
  EXPECT_EQ(load_run_config(kConfigDir + "run_euroc.yaml").frontend.clahe_clip_limit, 3.0);
  EXPECT_THROW(load_run_config(write_file("lidar_mapper:\n  features:\n    method: rays\n")), InputError);
}

TEST(RunConfig, SectionsReachTheirModulesAndMissingOnesKeepDefaults) {
  const OfflineRunConfig c = load_run_config(write_file(
      "frontend:\n  max_corners: 300\n  cross_check: false\nvio:\n  smoother:\n    window_size: 6\n"
      "lidar_mapper:\n  features:\n    half_window: 4\n  registration:\n    loss: huber\n  mapper:\n    dewarp: false\n"
      "loop_closure:\n  graph:\n    degenerate_sigma: 0.02\n    bearing_min_step_m: 0.05\n"
      "    tilt_final_only: false\n"));
  EXPECT_EQ(c.frontend.max_corners, 300);
  EXPECT_FALSE(c.frontend.cross_check);
  EXPECT_EQ(c.vio.smoother.window_size, 6);
  EXPECT_EQ(c.lidar.lidar.features.half_window, 4);
  EXPECT_EQ(c.lidar.lidar.registration.loss, lidar::RobustLoss::kHuber);
  EXPECT_FALSE(c.lidar.dewarp);
  EXPECT_EQ(c.graph.degenerate_sigma, 0.02);
  EXPECT_EQ(c.graph.bearing_min_step_m, 0.05);
  EXPECT_FALSE(c.graph.tilt_final_only);
  // Keys left out keep the mapper's defaults (not those of a bare LidarConfig).
  EXPECT_TRUE(c.lidar.lidar.registration.remap_degenerate_directions);
  EXPECT_EQ(c.lidar.lidar.registration.degenerate_min_eigenvalue_per_match,
            lidar::LidarMapperConfig{}.lidar.registration.degenerate_min_eigenvalue_per_match);

  OfflineRunConfig expected;
  expected.frontend.max_corners = 300;
  expected.frontend.cross_check = false;
  expected.vio.smoother.window_size = 6;
  expected.lidar.lidar.features.half_window = 4;
  expected.lidar.lidar.registration.loss = lidar::RobustLoss::kHuber;
  expected.lidar.dewarp = false;
  expected.graph.degenerate_sigma = 0.02;
  expected.graph.bearing_min_step_m = 0.05;
  expected.graph.tilt_final_only = false;
  EXPECT_EQ(run_config_yaml(c), run_config_yaml(expected));
  // The written config reads back to the same config.
  EXPECT_EQ(run_config_yaml(load_run_config(write_file(run_config_yaml(c)))), run_config_yaml(c));
  EXPECT_EQ(run_config_yaml(load_run_config(write_file(""))), run_config_yaml(OfflineRunConfig{}));
}

TEST(RunConfig, BadFilesNameTheFileAndTheKey) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"lidar:\n  rings:\n    num_rings: 32\n", "'lidar'"},
      {"frontend:\n  max_cornerz: 5\n", "frontend.max_cornerz"},
      {"frontend:\n  max_corners: many\n", "frontend.max_corners"},
      {"frontend:\n  klt_window_px: 20\n", "klt_window_px"},
      {"vio:\n  smoother:\n    window_size: 1\n", "smoother.window_size"},
      {"vio:\n  smoother:\n    pixel_sigma_px: .nan\n", "vio.smoother.pixel_sigma_px"},
      {"lidar_mapper:\n  rings:\n    num_rings: 0\n", "rings.num_rings"},
      {"lidar_mapper:\n  registration:\n    loss: l2\n", "lidar_mapper.registration.loss"},
      {"lidar_mapper:\n  registration:\n    tilt_prior_sigma_rad: -0.01\n", "tilt_prior_sigma_rad"},
      {"lidar_mapper:\n  mapper:\n    dewrap: true\n", "lidar_mapper.mapper.dewrap"},
      {"loop_closure:\n  graph:\n    degenerate_sigma: -0.01\n", "degenerate_sigma"},
      {"loop_closure:\n  graph:\n    bearing_min_step_m: -0.05\n", "bearing_min_step_m"},
      {"vio: [1, 2]\n", "'vio'"},
      {"- 1\n- 2\n", "map"},
      {"frontend: {max_corners: [1, 2\n", "malformed"},
  };
  for (const auto& [text, key] : cases) {
    const std::string path = write_file(text);
    try {
      load_run_config(path);
      ADD_FAILURE() << text << " was accepted";
    } catch (const InputError& e) {
      EXPECT_EQ(e.file(), path);
      EXPECT_NE(std::string(e.what()).find(key), std::string::npos) << text << " -> " << e.what();
    }
  }
  EXPECT_THROW(load_run_config((test::temp_dir() / "absent.yaml").string()), InputError);
}

}  // namespace
}  // namespace vilslam
