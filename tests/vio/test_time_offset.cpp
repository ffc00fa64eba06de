#include <gtest/gtest.h>

#include "vio/rotation_recording.h"
#include "vio/time_offset.h"

namespace vilslam {
namespace {

TEST(TimeOffset, RecoversTheOffsetAndTheGyroBias) {
  for (const double offset_s : {0.005, -0.012, 0.0}) {
    const Vec3 bias(0.02, -0.01, 0.03);
    const test::RotationRecording r = test::record_rotations(offset_s, 1.0, bias);
    const auto e = estimate_cam_time_offset(r.rotations, r.imu, r.R_I_C0, TimeOffsetConfig{});
    ASSERT_TRUE(e) << offset_s;
    EXPECT_NEAR(e->offset_s, offset_s, 0.0002) << offset_s;
    EXPECT_LT((e->gyro_bias_rad_s - bias).norm(), 0.002) << offset_s;
    EXPECT_GT(e->intervals, 500);
    if (offset_s != 0) {
      EXPECT_GT(e->rms_zero_offset_rad, 1.2 * e->rms_rad) << offset_s;
    }
  }
}

TEST(TimeOffset, WrongCameraRotationDoesNotFitAnOffset) {
  // The camera-IMU rotation transposed: the best offset no longer explains the camera's rotations.
  test::RotationRecording r = test::record_rotations(0.005, 1.0, Vec3::Zero());
  const auto good = estimate_cam_time_offset(r.rotations, r.imu, r.R_I_C0, TimeOffsetConfig{});
  const auto bad = estimate_cam_time_offset(r.rotations, r.imu, r.R_I_C0.transpose(), TimeOffsetConfig{});
  ASSERT_TRUE(good && bad);
  EXPECT_GT(bad->rms_rad, 10 * good->rms_rad);
}

TEST(TimeOffset, RefusesWithoutRotationOrIntervals) {
  const test::RotationRecording still = test::record_rotations(0.005, 0.01, Vec3::Zero());  // peak rate 0.01 rad/s
  EXPECT_FALSE(estimate_cam_time_offset(still.rotations, still.imu, still.R_I_C0, TimeOffsetConfig{}));
  test::RotationRecording few = test::record_rotations(0.005, 1.0, Vec3::Zero());
  few.rotations.resize(20);
  EXPECT_FALSE(estimate_cam_time_offset(few.rotations, few.imu, few.R_I_C0, TimeOffsetConfig{}));
}

}  // namespace
}  // namespace vilslam
