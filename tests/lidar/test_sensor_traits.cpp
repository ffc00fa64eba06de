#include <gtest/gtest.h>

#include "lidar/model_deviation.h"
#include "lidar/sensor_adaptation.h"
#include "lidar/sensor_traits.h"
#include "synthetic_scene.h"

namespace vilslam::lidar {
namespace {

const SE3 kStill(Quat::Identity(), Vec3(0.5, -1.0, 0.0));

TEST(SensorTraits, RingsAreReadOffTheElevationsWhenNoFieldNamesThem) {
  LidarScan spinning = test::sweep(test::box_room(), [](TimeNs) { return kStill; }, 0);
  const SensorTraits with_field = read_sensor_traits(spinning);
  EXPECT_TRUE(with_field.ring_field);
  EXPECT_EQ(with_field.rings, 16);
  EXPECT_TRUE(with_field.point_times);
  spinning.has_ring = false;
  for (LidarPoint& p : spinning.points) p.t_offset_s = 0.0f;
  const SensorTraits without = read_sensor_traits(spinning);
  EXPECT_FALSE(without.ring_field);
  EXPECT_FALSE(without.point_times);
  EXPECT_EQ(without.rings, 16);  // the 16 elevations, 2 deg apart
  EXPECT_TRUE(without.spinning());
  EXPECT_NEAR(without.min_elevation_deg, -15.0, 0.1);
  EXPECT_NEAR(without.max_elevation_deg, 15.0, 0.1);
  EXPECT_GT(without.azimuth_coverage, 0.99);
  EXPECT_GT(without.range_max_m, without.range_p90_m);
  EXPECT_GT(without.range_p90_m, without.range_median_m);
  EXPECT_GT(without.range_median_m, without.range_p10_m);
}

TEST(SensorTraits, ANonRepetitivePatternHasNoRings) {
  const SensorTraits t = read_sensor_traits(test::non_repetitive_sweep(test::box_room(), kStill));
  EXPECT_FALSE(t.ring_field);
  EXPECT_EQ(t.rings, 0);
  EXPECT_FALSE(t.spinning());
  EXPECT_TRUE(t.point_times);
  EXPECT_NE(sensor_traits_text(t).find("lidar_rings: 0 (none: a non-repetitive pattern)"), std::string::npos);
}

TEST(SensorTraits, TooFewReturnsLeaveThemUnreadAndNothingAdapts) {
  LidarScan sparse;
  sparse.has_ring = false;
  sparse.points.resize(50);
  for (LidarPoint& p : sparse.points) p.x = 5.0f;
  const SensorTraits t = read_sensor_traits(sparse);
  EXPECT_FALSE(t.read());
  EXPECT_EQ(t.points, 50u);
  EXPECT_FALSE(t.spinning());
  EXPECT_NE(sensor_traits_text(t).find("too few to read"), std::string::npos);
  const LidarMapperConfig kept = adapt_to_sensor(LidarMapperConfig{}, t);
  EXPECT_EQ(kept.lidar.features.method, FeatureMethod::kAuto);  // not taken for a non-repetitive sensor
}

TEST(SensorAdaptation, ANonRepetitiveSensorGetsNeighbourhoodFeaturesUnlessTheUserChose) {
  SensorTraits non_repetitive;
  non_repetitive.points = 20000;  // read, no rings
  LidarMapperConfig given;
  given.lidar.registration.source_surface_leaf_m = 0.3;  // the user's own value
  const LidarMapperConfig c = adapt_to_sensor(given, non_repetitive);
  EXPECT_EQ(c.lidar.features.method, FeatureMethod::kNeighbourhood);
  EXPECT_EQ(c.lidar.features.neighbourhood.candidate_stride, 1);
  EXPECT_EQ(c.lidar.features.neighbourhood.max_edges_per_cell, 0);
  EXPECT_EQ(c.lidar.registration.tilt_prior_sigma_rad, 0.0);
  EXPECT_EQ(c.lidar.registration.source_surface_leaf_m, 0.3);

  SensorTraits spinning = non_repetitive;
  spinning.rings = 16;
  const LidarMapperConfig kept = adapt_to_sensor(given, spinning);
  EXPECT_EQ(kept.lidar.features.method, FeatureMethod::kAuto);
  EXPECT_EQ(kept.lidar.features.neighbourhood.candidate_stride, given.lidar.features.neighbourhood.candidate_stride);
}

TEST(AzimuthClockVote, TheMajorityOfFiveMovingSweepsDecides) {
  AzimuthClockVote timed;
  for (double rms : {0.05, 0.05, 0.2, 0.05}) timed.vote(rms, 0.1);
  EXPECT_EQ(timed.state(), AzimuthClockVote::State::kUndecided);
  timed.vote(0.2, 0.1);
  EXPECT_EQ(timed.state(), AzimuthClockVote::State::kTimed);  // 3 of 5 fit better with azimuth times
  timed.vote(0.2, 0.1);
  EXPECT_EQ(timed.state(), AzimuthClockVote::State::kTimed);  // decided for the rest of the run

  AzimuthClockVote instant;
  for (double rms : {0.11, 0.05, 0.12, 0.05, 0.2}) instant.vote(rms, 0.1);
  EXPECT_EQ(instant.state(), AzimuthClockVote::State::kInstant);
}

TEST(ModelDeviation, RmsOfTheCorrectionsOfSweepsThatMoved) {
  const std::vector<Vec3> points = {Vec3(10, 0, 0), Vec3(0, 10, 0), Vec3(0, 0, 10), Vec3(-10, 0, 0)};
  ModelDeviation d;
  EXPECT_EQ(d.sigma_m(), 0.0);
  const SE3 moved(Quat::Identity(), Vec3(0.5, 0, 0));
  d.add(points, SE3(Quat::Identity(), Vec3(0.3, 0, 0)), SE3(Quat::Identity(), Vec3(0.05, 0, 0)));  // at rest
  EXPECT_EQ(d.sigma_m(), 0.0);
  d.add(points, SE3(Quat::Identity(), Vec3(0.3, 0, 0)), moved);
  d.add(points, SE3(Quat::Identity(), Vec3(0, 0.4, 0)), moved);
  EXPECT_NEAR(d.sigma_m(), std::sqrt((0.09 + 0.16) / 2.0), 1e-12);
  // A rotation displaces far points more: 0.01 rad at 10 m is 0.1 m.
  EXPECT_NEAR(rms_displacement_m(points, SE3(so3::exp(Vec3(0, 0, 0.01)), Vec3::Zero())),
              std::sqrt(3.0 / 4.0) * 2.0 * 10.0 * std::sin(0.005), 1e-9);
}

}  // namespace
}  // namespace vilslam::lidar
