// The LiDAR return model: missed echoes from dark and oblique surfaces, the spread of oblique footprints,
// mixed pixels at depth edges; an ideal model leaves the range noise alone.
#include <gtest/gtest.h>

#include <cmath>

#include "sim/lidar_returns.h"
#include "sim/lidar_sim.h"
#include "sim/rng.h"

namespace vilslam::sim {
namespace {

constexpr double kNoiseM = 0.02;

TEST(LidarReturns, IdealModelReturnsEveryHitWithTheRangeNoiseAlone) {
  const LidarReturnModel ideal = ideal_returns();
  for (std::uint64_t i = 0; i < 200; ++i) {
    const double expected = 90.0 + kNoiseM * rng_for(7, i).gaussian();
    EXPECT_EQ(returned_range_m(ideal, kNoiseM, 90.0, 40.0, 0.02, 0.05, 7, i), expected);
  }
}

TEST(LidarReturns, DarkAndObliqueSurfacesAreMissedFarAway) {
  const LidarReturnModel m = lidar_sensor("vlp16").returns;
  EXPECT_NEAR(detection_range_m(m, 0.1, 1.0), 57.0, 1e-9);
  EXPECT_NEAR(detection_range_m(m, 0.8, 1.0), 100.0, 0.5);             // the data sheet's 100 m
  EXPECT_LT(detection_range_m(m, 0.8, 0.1), detection_range_m(m, 0.8, 1.0) * 0.6);  // 84 deg incidence
  int near_kept = 0, far_kept = 0;
  for (std::uint64_t i = 0; i < 1000; ++i) {
    near_kept += returned_range_m(m, kNoiseM, 30.0, 0.0, 0.1, 1.0, 3, i) > 0;
    far_kept += returned_range_m(m, kNoiseM, 80.0, 0.0, 0.1, 1.0, 3, i) > 0;
  }
  EXPECT_EQ(near_kept, 1000);  // 30 m is 4.7 sigma inside the 57 m of a 10 % target
  EXPECT_EQ(far_kept, 0);
}

TEST(LidarReturns, ObliqueFootprintsSpreadTheRange) {
  const LidarReturnModel m = lidar_sensor("vlp16").returns;
  const double cos80 = std::cos(80.0 * M_PI / 180.0);
  const double footprint_m = 0.5 * 10.0 * 0.003 * std::tan(80.0 * M_PI / 180.0);  // 8.5 cm
  EXPECT_NEAR(range_sigma_m(m, kNoiseM, 10.0, cos80), std::hypot(kNoiseM, footprint_m), 1e-12);
  EXPECT_NEAR(range_sigma_m(m, kNoiseM, 10.0, 1.0), kNoiseM, 1e-15);
  double sum_sq = 0;
  const int n = 4000;
  for (int i = 0; i < n; ++i) {
    const double r = returned_range_m(m, kNoiseM, 10.0, 0.0, 0.9, cos80, 11, i);
    sum_sq += (r - 10.0) * (r - 10.0);
  }
  EXPECT_NEAR(std::sqrt(sum_sq / n), std::hypot(kNoiseM, footprint_m), 0.005);
}

TEST(LidarReturns, BeamsAtADepthEdgeReturnMixedRanges) {
  const LidarReturnModel m = lidar_sensor("vlp16").returns;  // half of the edge beams mixed
  int between = 0, outside = 0;
  const int n = 2000;
  for (int i = 0; i < n; ++i) {
    const double r = returned_range_m(m, kNoiseM, 5.0, 9.0, 0.9, 1.0, 5, i);
    if (r > 5.0 + 5 * kNoiseM && r < 9.0) ++between;
    if (r < 5.0 - 5 * kNoiseM || r > 9.0 + 5 * kNoiseM) ++outside;
  }
  EXPECT_NEAR(between / double(n), 0.5 * (1.0 - 0.1 / 4.0), 0.04);  // a mixed draw within 0.1 m of 5 m looks unmixed
  EXPECT_EQ(outside, 0);
  for (int i = 0; i < 200; ++i)  // no edge: a jump below the threshold mixes nothing
    EXPECT_LT(std::abs(returned_range_m(m, kNoiseM, 5.0, 5.2, 0.9, 1.0, 5, i) - 5.0), 5 * kNoiseM);
}

}  // namespace
}  // namespace vilslam::sim
