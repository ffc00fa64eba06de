#include "calib/mount_rotation.h"

#include <gtest/gtest.h>

#include <cmath>

#include "calib/turning_route.h"

namespace vilslam::calib {
namespace {

using test::kDeg;
using test::lidar_route;
using test::turning_rig;
using test::TurningRig;

const Mat3 kNominal = so3::exp(Vec3(0.0, 0.0, M_PI / 2));  // the LiDAR turned 90 deg about the vertical
const Vec3 kTrueCorrection = Vec3(0.4, -0.3, 0.25) * kDeg;   // the mount's real offset, in L
const Vec3 kGyroBias(0.01, -0.01, 0.005);  // rad/s: 1.1 deg over a 2 s window, twice the mount's error

TEST(MountRotation, TurnsAboutTheVerticalRecoverTheMountsTiltAndLeaveItsYawAtTheNominal) {
  const TurningRig rig = turning_rig(0.0, kGyroBias);
  const Trajectory lidar = lidar_route(rig.T_W_I, kNominal * so3::exp(kTrueCorrection), 0.03 * kDeg, 1);
  const MountRotationEstimate e = estimate_mount_rotation(rig.imu, lidar, kNominal);
  ASSERT_GT(e.turning_windows, 20);
  EXPECT_GT(e.windows, e.turning_windows);
  // L's z is the vertical here: its x and y components are the tilt the turns show.
  EXPECT_NEAR(e.correction_rad.x(), kTrueCorrection.x(), 0.02 * kDeg);
  EXPECT_NEAR(e.correction_rad.y(), kTrueCorrection.y(), 0.02 * kDeg);
  // The yaw is unobservable from yaw turns: it keeps the nominal value, and the estimate says so.
  EXPECT_LT(std::abs(e.correction_rad.z()), 0.01 * kDeg);
  EXPECT_EQ(e.estimated_directions, 2);
  EXPECT_GT(std::abs(e.kept_direction.z()), 0.999);
  EXPECT_GT(e.covariance_rad2(0, 0), 0.0);
  EXPECT_LT(std::sqrt(e.covariance_rad2(0, 0)), 0.02 * kDeg);
  EXPECT_LT(std::abs(e.covariance_rad2(2, 2)), 1e-10);  // (1e-5 rad)^2
  // The gyroscope's bias comes out with it.
  EXPECT_LT((e.gyro_bias_rad_s - kGyroBias).norm(), 2e-4) << e.gyro_bias_rad_s.transpose();
}

TEST(MountRotation, RollAndPitchMotionAlsoShowTheYaw) {
  const TurningRig rig = turning_rig(0.3, kGyroBias);
  const Trajectory lidar = lidar_route(rig.T_W_I, kNominal * so3::exp(kTrueCorrection), 0.03 * kDeg, 2);
  const MountRotationEstimate e = estimate_mount_rotation(rig.imu, lidar, kNominal);
  EXPECT_EQ(e.estimated_directions, 3);
  EXPECT_LT((e.correction_rad - kTrueCorrection).norm(), 0.05 * kDeg) << e.correction_rad.transpose() / kDeg;
}

TEST(MountRotation, AMisregisteredStretchDoesNotPullTheEstimate) {
  const TurningRig rig = turning_rig(0.0, kGyroBias);
  Trajectory lidar = lidar_route(rig.T_W_I, kNominal * so3::exp(kTrueCorrection), 0.03 * kDeg, 3);
  // From 20 s to 24 s the LiDAR odometry is 3 deg off in roll (a registration that slipped and came back).
  for (std::size_t k = 200; k < 240; ++k) {
    lidar[k].T_W_B = lidar[k].T_W_B * SE3(so3::exp(Vec3(3.0 * kDeg, 0.0, 0.0)), Vec3::Zero());
  }
  const MountRotationEstimate robust = estimate_mount_rotation(rig.imu, lidar, kNominal);
  EXPECT_NEAR(robust.correction_rad.x(), kTrueCorrection.x(), 0.05 * kDeg);
  EXPECT_NEAR(robust.correction_rad.y(), kTrueCorrection.y(), 0.05 * kDeg);
  // Without the Huber weights the same stretch moves it further.
  MountRotationConfig squared;
  squared.huber_scales = 1e9;
  const MountRotationEstimate plain = estimate_mount_rotation(rig.imu, lidar, kNominal, squared);
  EXPECT_GT((plain.correction_rad - kTrueCorrection).head<2>().norm(),
            2.0 * (robust.correction_rad - kTrueCorrection).head<2>().norm());
}

TEST(MountRotation, ARouteThatDoesNotTurnKeepsTheNominal) {
  TurningRig still;
  for (int k = 0; k <= 6000; ++k) {
    ImuSample s;
    s.t_ns = static_cast<TimeNs>(k) * 5'000'000;
    still.imu.push_back(s);
    if (k % 20 == 0) still.T_W_I.push_back({s.t_ns, SE3(Mat3::Identity(), Vec3(0.005 * k, 0, 0))});
  }
  const Trajectory lidar = lidar_route(still.T_W_I, kNominal * so3::exp(kTrueCorrection), 0.03 * kDeg, 4);
  const MountRotationEstimate e = estimate_mount_rotation(still.imu, lidar, kNominal);
  EXPECT_GT(e.windows, 0);
  EXPECT_EQ(e.turning_windows, 0);
  EXPECT_EQ(e.estimated_directions, 0);
  EXPECT_LT(e.correction_rad.norm(), 1e-12);
}

TEST(MountRotation, WindowsAcrossAGapInEitherStreamAreLeftOut) {
  const TurningRig rig = turning_rig(0.0, kGyroBias);
  const Trajectory lidar = lidar_route(rig.T_W_I, kNominal * so3::exp(kTrueCorrection), 0.03 * kDeg, 5);
  const auto outside = [](TimeNs t, TimeNs from, TimeNs to) { return t < from || t > to; };
  Trajectory lidar_gap;  // 20 s missing
  for (const TimedPose& p : lidar) {
    if (outside(p.t_ns, 10'000'000'000, 30'000'000'000)) lidar_gap.push_back(p);
  }
  std::vector<ImuSample> imu_gap;  // 20 s missing elsewhere
  for (const ImuSample& s : rig.imu) {
    if (outside(s.t_ns, 35'000'000'000, 55'000'000'000)) imu_gap.push_back(s);
  }
  const MountRotationEstimate full = estimate_mount_rotation(rig.imu, lidar, kNominal);
  const MountRotationEstimate part = estimate_mount_rotation(imu_gap, lidar_gap, kNominal);
  EXPECT_LT(part.windows, full.windows / 3 + 3);
  EXPECT_GT(part.turning_windows, 0);
  EXPECT_NEAR(part.correction_rad.x(), kTrueCorrection.x(), 0.05 * kDeg);
}

}  // namespace
}  // namespace vilslam::calib
