#pragma once
// Comparisons of calibration values shared by the io tests.
#include <gtest/gtest.h>

#include "common/calibration.h"

namespace vilslam::test {

inline void expect_same_camera(const CameraIntrinsics& a, const CameraIntrinsics& b) {
  EXPECT_EQ(a.width_px, b.width_px);
  EXPECT_EQ(a.height_px, b.height_px);
  EXPECT_EQ(a.fx, b.fx);
  EXPECT_EQ(a.fy, b.fy);
  EXPECT_EQ(a.cx, b.cx);
  EXPECT_EQ(a.cy, b.cy);
  EXPECT_EQ(a.distortion, b.distortion);
  EXPECT_EQ(a.distortion_coeffs, b.distortion_coeffs);
  EXPECT_EQ(a.rate_hz, b.rate_hz);
}

}  // namespace vilslam::test
