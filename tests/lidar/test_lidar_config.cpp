#include <gtest/gtest.h>

#include <fstream>

#include "common/error.h"
#include "lidar/lidar_config.h"
#include "test_util.h"

namespace vilslam::lidar {
namespace {

TEST(LidarConfig, LoadsOverridesAndKeepsDefaults) {
  const std::string path = (test::temp_dir() / "lidar.yaml").string();
  std::ofstream(path) << "rings:\n  num_rings: 32\n  min_elevation_deg: -30.67\nfeatures:\n  sectors_per_ring: 8\n"
                         "map:\n  surfaces:\n    min_point_spacing_m: 0.5\nregistration:\n  loss: huber\n"
                         "  remap_degenerate_directions: true\n  num_neighbors: 6\n  tilt_prior_sigma_rad: 0.005\n"
                         "  max_normal_angle_deg: 10\n";
  const LidarConfig c = load_lidar_config(path);
  EXPECT_EQ(c.rings.num_rings, 32);
  EXPECT_DOUBLE_EQ(c.rings.min_elevation_deg, -30.67);
  EXPECT_DOUBLE_EQ(c.rings.max_elevation_deg, RingConfig{}.max_elevation_deg);
  EXPECT_EQ(c.features.sectors_per_ring, 8);
  EXPECT_DOUBLE_EQ(c.map.surfaces.min_point_spacing_m, 0.5);
  EXPECT_DOUBLE_EQ(c.map.edges.min_point_spacing_m, FeatureMapConfig{}.edges.min_point_spacing_m);
  EXPECT_EQ(c.registration.loss, RobustLoss::kHuber);
  EXPECT_TRUE(c.registration.remap_degenerate_directions);
  EXPECT_EQ(c.registration.association.num_neighbors, 6);
  EXPECT_DOUBLE_EQ(c.registration.tilt_prior_sigma_rad, 0.005);
  EXPECT_DOUBLE_EQ(c.registration.association.max_normal_angle_deg, 10.0);
  EXPECT_DOUBLE_EQ(LidarConfig{}.registration.association.max_normal_angle_deg, 0.0);  // off unless configured
}

TEST(LidarConfig, RejectsUnknownKeysBadValuesAndMissingFiles) {
  const auto dir = test::temp_dir();
  std::ofstream(dir / "typo.yaml") << "features:\n  sectors_per_rign: 8\n";
  try {
    load_lidar_config((dir / "typo.yaml").string());
    FAIL() << "typo accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("features.sectors_per_rign"), std::string::npos) << e.what();
    EXPECT_EQ(e.line(), 2);
  }
  std::ofstream(dir / "type.yaml") << "rings:\n  num_rings: many\n";
  EXPECT_THROW(load_lidar_config((dir / "type.yaml").string()), InputError);
  std::ofstream(dir / "zero.yaml") << "rings:\n  num_rings: 0\n";
  EXPECT_THROW(load_lidar_config((dir / "zero.yaml").string()), InputError);
  std::ofstream(dir / "sigma.yaml") << "registration:\n  tilt_prior_sigma_rad: -0.005\n";
  EXPECT_THROW(load_lidar_config((dir / "sigma.yaml").string()), InputError);
  std::ofstream(dir / "normal.yaml") << "registration:\n  max_normal_angle_deg: 90\n";
  EXPECT_THROW(load_lidar_config((dir / "normal.yaml").string()), InputError);
  EXPECT_THROW(load_lidar_config((dir / "absent.yaml").string()), InputError);
}

}  // namespace
}  // namespace vilslam::lidar
