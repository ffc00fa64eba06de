#include "calib/mount_rotation.h"

#include <gtest/gtest.h>

#include <cmath>

#include "calib/turning_route.h"

namespace vilslam::calib {
namespace {

using test::imu_route;
using test::kDeg;
using test::lidar_route;

const Mat3 kNominal = so3::exp(Vec3(0.0, 0.0, M_PI / 2));  // the LiDAR turned 90 deg about the vertical
const Vec3 kTrueCorrection = Vec3(0.4, -0.3, 0.25) * kDeg;   // the mount's real offset, in L

TEST(MountRotation, TurnsAboutTheVerticalRecoverTheMountsTiltAndLeaveItsYawAtTheNominal) {
  const Trajectory imu = imu_route(0.0);
  const Trajectory lidar = lidar_route(imu, kNominal * so3::exp(kTrueCorrection), 0.03 * kDeg, 1);
  const MountRotationEstimate e = estimate_mount_rotation(imu, lidar, kNominal);
  ASSERT_GT(e.windows, 20);
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
}

TEST(MountRotation, RollAndPitchMotionAlsoShowTheYaw) {
  const Trajectory imu = imu_route(0.3);
  const Trajectory lidar = lidar_route(imu, kNominal * so3::exp(kTrueCorrection), 0.03 * kDeg, 2);
  const MountRotationEstimate e = estimate_mount_rotation(imu, lidar, kNominal);
  EXPECT_EQ(e.estimated_directions, 3);
  EXPECT_LT((e.correction_rad - kTrueCorrection).norm(), 0.05 * kDeg) << e.correction_rad.transpose() / kDeg;
}

TEST(MountRotation, AMisregisteredStretchDoesNotPullTheEstimate) {
  const Trajectory imu = imu_route(0.0);
  Trajectory lidar = lidar_route(imu, kNominal * so3::exp(kTrueCorrection), 0.03 * kDeg, 3);
  // From 20 s to 24 s the LiDAR odometry is 3 deg off in roll (a registration that slipped and came back).
  for (std::size_t k = 200; k < 240; ++k) {
    lidar[k].T_W_B = lidar[k].T_W_B * SE3(so3::exp(Vec3(3.0 * kDeg, 0.0, 0.0)), Vec3::Zero());
  }
  const MountRotationEstimate robust = estimate_mount_rotation(imu, lidar, kNominal);
  EXPECT_NEAR(robust.correction_rad.x(), kTrueCorrection.x(), 0.05 * kDeg);
  EXPECT_NEAR(robust.correction_rad.y(), kTrueCorrection.y(), 0.05 * kDeg);
  // Without the Huber weights the same stretch moves it further.
  MountRotationConfig squared;
  squared.huber_scales = 1e9;
  const MountRotationEstimate plain = estimate_mount_rotation(imu, lidar, kNominal, squared);
  EXPECT_GT((plain.correction_rad - kTrueCorrection).head<2>().norm(),
            2.0 * (robust.correction_rad - kTrueCorrection).head<2>().norm());
}

TEST(MountRotation, ARouteThatDoesNotTurnKeepsTheNominal) {
  Trajectory imu;
  for (int k = 0; k <= 300; ++k) imu.push_back({static_cast<TimeNs>(k) * 100'000'000, SE3(Mat3::Identity(), Vec3(0.1 * k, 0, 0))});
  const Trajectory lidar = lidar_route(imu, kNominal * so3::exp(kTrueCorrection), 0.03 * kDeg, 4);
  const MountRotationEstimate e = estimate_mount_rotation(imu, lidar, kNominal);
  EXPECT_EQ(e.windows, 0);
  EXPECT_EQ(e.estimated_directions, 0);
  EXPECT_LT(e.correction_rad.norm(), 1e-12);
}

TEST(MountRotation, WindowsAcrossAGapInEitherTrajectoryAreLeftOut) {
  const Trajectory imu = imu_route(0.0);
  const Trajectory lidar = lidar_route(imu, kNominal * so3::exp(kTrueCorrection), 0.03 * kDeg, 5);
  Trajectory gappy;
  for (const TimedPose& p : lidar) {
    if (p.t_ns < 10'000'000'000 || p.t_ns > 50'000'000'000) gappy.push_back(p);  // 40 s missing
  }
  const MountRotationEstimate full = estimate_mount_rotation(imu, lidar, kNominal);
  const MountRotationEstimate part = estimate_mount_rotation(imu, gappy, kNominal);
  EXPECT_LT(part.windows, full.windows / 2);
  EXPECT_GT(part.windows, 0);
  EXPECT_NEAR(part.correction_rad.x(), kTrueCorrection.x(), 0.05 * kDeg);
}

}  // namespace
}  // namespace vilslam::calib
