#include <gtest/gtest.h>

#include <cstring>

#include "lidar/registration.h"
#include "synthetic_scene.h"

namespace vilslam::lidar {
namespace {

FeatureScan features_at(const test::Scene& scene, const SE3& T_W_L, const RingConfig& rings = {}) {
  const LidarScan scan = test::sweep(scene, [T_W_L](TimeNs) { return T_W_L; }, 0);
  return extract_features(scan, rings, FeatureConfig{});
}

double angle_deg(const SE3& a, const SE3& b) { return so3::log((a.inverse() * b).rotation()).norm() * 180.0 / M_PI; }

TEST(Registration, RecoversASyntheticOffsetFromIdentity) {
  const test::Scene scene = test::box_room();
  const SE3 T_W_target;  // the map frame is the target scan's frame
  const SE3 T_W_source(so3::exp(Vec3(0.01, -0.005, 0.07)), Vec3(0.4, -0.25, 0.05));
  FeatureMap map;
  map.insert(features_at(scene, T_W_target), T_W_target);
  const RegistrationResult r = register_scan(features_at(scene, T_W_source), map, SE3(), RegistrationConfig{});
  EXPECT_TRUE(r.converged) << r.outer_iterations << " " << (r.T_W_L.translation() - T_W_source.translation()).transpose();
  EXPECT_LT((r.T_W_L.translation() - T_W_source.translation()).norm(), 0.01);
  EXPECT_LT(angle_deg(r.T_W_L, T_W_source), 0.1);
  EXPECT_GT(r.matched_fraction, 0.5);
  EXPECT_GT(r.inlier_fraction, 0.9);  // the rest see parts of the room the target scan did not
  EXPECT_FALSE(r.degeneracy.degenerate());
}

TEST(Registration, IsBitIdenticalAcrossRuns) {
  const test::Scene scene = test::box_room();
  FeatureMap map;
  map.insert(features_at(scene, SE3()), SE3());
  const FeatureScan source = features_at(scene, SE3(so3::exp(Vec3(0, 0, 0.05)), Vec3(0.3, 0.1, 0)));
  const RegistrationResult a = register_scan(source, map, SE3(), RegistrationConfig{});
  const RegistrationResult b = register_scan(source, map, SE3(), RegistrationConfig{});
  const Mat4 Ta = a.T_W_L.matrix(), Tb = b.T_W_L.matrix();
  EXPECT_EQ(std::memcmp(Ta.data(), Tb.data(), sizeof(double) * 16), 0);
  EXPECT_EQ(a.rms_residual_m, b.rms_residual_m);
}

// A long corridor (its ends beyond the range limit): nothing constrains motion along it.
test::Scene corridor() { return {{Vec3(-500, -2, -1.5), Vec3(500, 2, 2)}, {}}; }

TEST(Degeneracy, CorridorIsDegenerateAlongItsAxis) {
  RingConfig rings;
  rings.max_range_m = 40.0;
  FeatureMap map;
  map.insert(features_at(corridor(), SE3(), rings), SE3());
  const SE3 T_W_source(so3::exp(Vec3(0, 0, 0.03)), Vec3(0.5, 0.1, 0.0));
  const RegistrationResult r = register_scan(features_at(corridor(), T_W_source, rings), map, SE3(), RegistrationConfig{});
  ASSERT_TRUE(r.degeneracy.degenerate());
  ASSERT_EQ(r.degeneracy.degenerate_directions.size(), 1u);
  EXPECT_GT(std::abs(r.degeneracy.degenerate_directions[0](0)), 0.99);  // translation along x
  EXPECT_LT(r.degeneracy.min_max_ratio, 1e-3);
  // The well-conditioned directions are still found.
  EXPECT_NEAR(r.T_W_L.translation().y(), 0.1, 0.01);
  EXPECT_LT(angle_deg(r.T_W_L, SE3(T_W_source.quat(), r.T_W_L.translation())), 0.1);
}

TEST(Degeneracy, RemappingKeepsThePriorAlongDegenerateDirections) {
  RingConfig rings;
  rings.max_range_m = 40.0;
  FeatureMap map;
  map.insert(features_at(corridor(), SE3(), rings), SE3());
  const SE3 T_W_source(so3::exp(Vec3(0, 0, 0.03)), Vec3(0.5, 0.1, 0.0));
  // The prior (e.g. from VIO) knows the motion along the corridor, but not the lateral offset and yaw.
  const SE3 prior(Quat::Identity(), Vec3(0.5, 0.0, 0.0));
  RegistrationConfig config;
  config.remap_degenerate_directions = true;
  const RegistrationResult r = register_scan(features_at(corridor(), T_W_source, rings), map, prior, config);
  EXPECT_NEAR(r.T_W_L.translation().x(), 0.5, 0.005);
  config.remap_degenerate_directions = false;
  const RegistrationResult free = register_scan(features_at(corridor(), T_W_source, rings), map, prior, config);
  // Without remapping the unconstrained direction wanders off the prior.
  EXPECT_GT(std::abs(free.T_W_L.translation().x() - 0.5), 0.05);
  EXPECT_NEAR(r.T_W_L.translation().y(), 0.1, 0.01);
  EXPECT_LT(angle_deg(r.T_W_L, T_W_source), 0.1);
}

}  // namespace
}  // namespace vilslam::lidar
