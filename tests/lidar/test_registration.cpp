#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <iostream>

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

// Two parallel walls 2 m either side, no floor, ceiling or end within range: they fix the lateral position,
// roll and yaw; the position along the corridor, the height and the pitch are free.
test::Scene two_walls() { return {{Vec3(-500, -2, -500), Vec3(500, 2, 500)}, {}}; }

double pitch_rad(const SE3& T_W_L) {
  const Vec3 up_L = T_W_L.rotation().transpose() * Vec3::UnitZ();
  return std::atan2(-up_L.x(), up_L.z());
}

// How much of the pitch direction (rotation about L's y, [rho; phi] = e_4) the degenerate directions span.
double degenerate_pitch_share(const Degeneracy& d) {
  double share = 0.0;
  for (const Vec6& v : d.degenerate_directions) share += v(4) * v(4);
  return share;
}

TEST(TiltPrior, HoldsThePitchTheMapLeavesFree) {
  RingConfig rings;
  rings.max_range_m = 40.0;
  FeatureMap map;
  map.insert(features_at(two_walls(), SE3(), rings), SE3());
  const SE3 T_W_source(so3::exp(Vec3(0.0, 0.0087, 0.03)), Vec3(0.5, 0.1, 0.0));  // pitched 0.5 deg
  const FeatureScan source = features_at(two_walls(), T_W_source, rings);
  // The initial guess (previous pose and the prior's motion) has drifted 1 deg in pitch; the gravity-referenced
  // prior knows the true tilt.
  const SE3 init(so3::exp(Vec3(0.0, 0.0087 + 0.0175, 0.0)), Vec3(0.5, 0.0, 0.0));
  const Vec3 up_L_prior = T_W_source.rotation().transpose() * Vec3::UnitZ();
  RegistrationConfig config;
  config.remap_degenerate_directions = true;
  config.degenerate_min_eigenvalue_per_match = 0.03;  // the mapper's
  config.tilt_prior_sigma_rad = 0.005;
  const RegistrationResult with = register_scan(source, map, init, config, up_L_prior);
  const RegistrationResult without = register_scan(source, map, init, config);  // no prior: off
  config.remap_degenerate_directions = false;
  const RegistrationResult with_free = register_scan(source, map, init, config, up_L_prior);
  config.tilt_prior_sigma_rad = 0.0;  // off
  const RegistrationResult free = register_scan(source, map, init, config, up_L_prior);
  config.tilt_prior_sigma_rad = 0.005;
  const double truth = pitch_rad(T_W_source), deg = 180.0 / M_PI;
  std::cout << "pitch error [deg]: prior + remapping " << (pitch_rad(with.T_W_L) - truth) * deg
            << ", prior without remapping " << (pitch_rad(with_free.T_W_L) - truth) * deg << ", remapping alone "
            << (pitch_rad(without.T_W_L) - truth) * deg << ", neither " << (pitch_rad(free.T_W_L) - truth) * deg
            << "; degenerate directions " << with.degeneracy.degenerate_directions.size() << " with the prior, "
            << without.degeneracy.degenerate_directions.size() << " without\n";
  // The prior's information enters the degeneracy analysis: pitch is no longer degenerate, so the remapping
  // does not freeze it at the initial guess; along the corridor and vertically the initial guess is kept.
  EXPECT_LT(degenerate_pitch_share(with.degeneracy), 1e-3);
  EXPECT_GT(degenerate_pitch_share(without.degeneracy), 0.99);
  EXPECT_EQ(with.degeneracy.degenerate_directions.size(), 2u);
  EXPECT_NEAR(pitch_rad(with.T_W_L), truth, 2e-4);
  EXPECT_NEAR(pitch_rad(with_free.T_W_L), truth, 2e-4);
  EXPECT_NEAR(pitch_rad(without.T_W_L), pitch_rad(init), 2e-4);  // frozen at the drifted guess
  EXPECT_GT(std::abs(pitch_rad(free.T_W_L) - truth), 5e-3);      // free: not held at the truth
  EXPECT_NEAR(with.T_W_L.translation().x(), 0.5, 0.005);
  EXPECT_NEAR(with.T_W_L.translation().y(), 0.1, 0.01);
  // Roll and yaw come from the walls and agree with the prior's roll.
  EXPECT_LT(angle_deg(with.T_W_L, T_W_source), 0.05);
  // Deterministic with the prior as without.
  config.remap_degenerate_directions = true;
  const RegistrationResult again = register_scan(source, map, init, config, up_L_prior);
  const Mat4 Ta = with.T_W_L.matrix(), Tb = again.T_W_L.matrix();
  EXPECT_EQ(std::memcmp(Ta.data(), Tb.data(), sizeof(double) * 16), 0);
}

}  // namespace
TEST(TiltPrior, AnUncertainPriorGivesWayToTheMap) {
  // A room constrains pitch; the gravity-referenced prior is 1 deg off in pitch (a VIO just started again). Told
  // how uncertain it is (its own tilt sigma, 1 deg), the prior weighs less than at the configured 0.3 deg.
  const test::Scene scene = test::box_room();
  FeatureMap map;
  map.insert(features_at(scene, SE3()), SE3());
  const SE3 T_W_source(so3::exp(Vec3(0.0, 0.0, 0.05)), Vec3(0.3, -0.2, 0.0));
  const FeatureScan source = features_at(scene, T_W_source);
  const Vec3 up_L_wrong = (T_W_source.rotation() * so3::exp(Vec3(0.0, 0.0175, 0.0))).transpose() * Vec3::UnitZ();
  RegistrationConfig config;
  config.tilt_prior_sigma_rad = 0.00524;
  const double truth = pitch_rad(T_W_source), deg = 180.0 / M_PI;
  const double confident = std::abs(pitch_rad(register_scan(source, map, SE3(), config, up_L_wrong).T_W_L) - truth);
  const double uncertain =
      std::abs(pitch_rad(register_scan(source, map, SE3(), config, up_L_wrong, 0.0175).T_W_L) - truth);
  const double below_config =  // a prior sigma under the configured one changes nothing
      std::abs(pitch_rad(register_scan(source, map, SE3(), config, up_L_wrong, 0.001).T_W_L) - truth);
  config.tilt_prior_sigma_rad = 0.0;  // off
  const double map_alone = std::abs(pitch_rad(register_scan(source, map, SE3(), config, up_L_wrong).T_W_L) - truth);
  std::cout << "pitch error [deg]: prior at 0.3 deg " << confident * deg << ", at 1 deg " << uncertain * deg
            << ", no prior " << map_alone * deg << "\n";
  // The pull towards the wrong prior (beyond the map's own error) shrinks about as the weight does, 1/11.
  EXPECT_LT(uncertain - map_alone, 0.25 * (confident - map_alone));
  EXPECT_DOUBLE_EQ(below_config, confident);
}

}  // namespace vilslam::lidar
