#include <gtest/gtest.h>

#include <algorithm>

#include "lidar/azimuth_times.h"
#include "synthetic_scene.h"

namespace vilslam::lidar {
namespace {

std::vector<float> times_of(const LidarScan& scan) {
  std::vector<float> t;
  for (const LidarPoint& p : scan.points) t.push_back(p.t_offset_s);
  return t;
}

// Strips the times, recovers them from the azimuth and returns the largest error against the truth.
double largest_time_error(LidarScan scan) {
  const std::vector<float> truth = times_of(scan);
  for (LidarPoint& p : scan.points) p.t_offset_s = 0.0f;
  EXPECT_FALSE(has_point_times(scan));
  assign_azimuth_times(scan, 0.1);
  double worst = 0.0;
  for (std::size_t i = 0; i < truth.size(); ++i) worst = std::max(worst, double(std::abs(scan.points[i].t_offset_s - truth[i])));
  return worst;
}

TEST(AzimuthTimes, RecoverTheFiringTimesInAnyPointOrderAndSpinDirection) {
  // 1,800 columns of 16 rings, counter-clockwise from -180 deg over 0.1 s, listed column by column.
  const LidarScan raw = test::sweep(test::box_room(), test::moving_pose, 0);
  ASSERT_TRUE(has_point_times(raw));
  EXPECT_LT(largest_time_error(raw), 1e-6);

  LidarScan by_ring = raw;  // as drivers that list the points ring by ring
  std::stable_sort(by_ring.points.begin(), by_ring.points.end(),
                   [](const LidarPoint& a, const LidarPoint& b) { return a.ring < b.ring; });
  EXPECT_LT(largest_time_error(by_ring), 1e-6);

  LidarScan clockwise = raw;  // mirrored: the head turns the other way, as a Velodyne's does
  for (LidarPoint& p : clockwise.points) p.y = -p.y;
  EXPECT_LT(largest_time_error(clockwise), 1e-6);

  LidarScan no_ring = raw;  // no ring field: one group in firing order
  no_ring.has_ring = false;
  EXPECT_LT(largest_time_error(no_ring), 1e-6);

  // The wrong spin direction would give most points the mirrored share of the turn.
  LidarScan stripped = raw;
  for (LidarPoint& p : stripped.points) p.t_offset_s = 0.0f;
  assign_azimuth_times(stripped, 0.1);
  const auto mid = stripped.points.size() / 4;  // a quarter turn in: 0.025 s, not 0.075 s
  EXPECT_NEAR(stripped.points[mid].t_offset_s, 0.025, 1e-4);
}

TEST(AzimuthTimes, PointsAtTheStartAzimuthOpenOrCloseTheSweepByFileOrder) {
  LidarScan scan = test::sweep(test::box_room(), [](TimeNs) { return SE3(); }, 0);
  // The head turns a little past a full turn: the last points repeat the first column's azimuths.
  for (int ring = 0; ring < 16; ++ring) {
    LidarPoint p = scan.points[ring];
    p.t_offset_s = 0.1f;
    scan.points.push_back(p);
  }
  // A ring's first return lies 1 deg behind the start (beam azimuth offsets of multi-beam heads).
  LidarPoint behind = scan.points[3];
  const double a = std::atan2(behind.y, behind.x) - M_PI / 180.0, r = std::hypot(behind.x, behind.y);
  behind.x = static_cast<float>(r * std::cos(a));
  behind.y = static_cast<float>(r * std::sin(a));
  scan.points.insert(scan.points.begin() + 3, behind);
  for (LidarPoint& p : scan.points) p.t_offset_s = 0.0f;
  assign_azimuth_times(scan, 0.1);
  EXPECT_EQ(scan.points[3].t_offset_s, 0.0f);
  for (std::size_t i = scan.points.size() - 16; i < scan.points.size(); ++i) {
    EXPECT_NEAR(scan.points[i].t_offset_s, 0.1, 1e-6);
  }
  EXPECT_NEAR(scan.end_t_ns(), 100'000'000, 1000);
}

TEST(AzimuthTimes, OnlySpinningSweepsWithoutTimesAreFilled) {
  const LidarScan raw = test::sweep(test::box_room(), test::moving_pose, 0);
  const SensorTraits spinning = read_sensor_traits(raw);  // 16 rings
  ASSERT_TRUE(spinning.spinning());
  LidarScan with_times = raw;
  EXPECT_FALSE(fill_missing_point_times(with_times, spinning, 10.0));
  EXPECT_EQ(times_of(with_times), times_of(raw));

  LidarScan without = raw;
  for (LidarPoint& p : without.points) p.t_offset_s = 0.0f;
  SensorTraits non_repetitive = spinning;
  non_repetitive.ring_field = false;
  non_repetitive.rings = 0;  // no azimuth order to recover
  LidarScan kept = without;
  EXPECT_FALSE(fill_missing_point_times(kept, non_repetitive, 10.0));
  EXPECT_FALSE(has_point_times(kept));

  EXPECT_TRUE(fill_missing_point_times(without, spinning, 20.0));
  EXPECT_NEAR(ns_to_s(without.end_t_ns() - without.t_ns), 0.05, 1e-4);
}

}  // namespace
}  // namespace vilslam::lidar
