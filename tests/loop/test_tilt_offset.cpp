// The mount's tilt error in the VIO's up directions (loop/tilt_offset.h): a rotation fixed in L is told from the
// map's own tilt, fixed in the world, by the rig's turns, and without turns it is left to the map's tilt.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "loop/tilt_offset.h"

namespace vilslam::loop {
namespace {

const Vec3 kMountRad(0.003, -0.008, 0.0);  // 0.17 and -0.46 deg
const Vec3 kMapTiltRad(0.004, 0.002, 0.0);

// The offset estimated from poses at these headings, the measured up directions carrying both tilts.
Vec3 estimate(const std::vector<double>& yaws_rad) {
  UpOffsetSamples samples;
  for (double yaw : yaws_rad) {
    const Mat3 R_W_L = so3::rot_z(yaw);
    const Vec3 own_up_L = R_W_L.transpose() * Vec3::UnitZ();
    // The model's epsilon_k turns the measured up onto the LiDAR's own.
    const Vec3 epsilon = kMountRad + R_W_L.transpose() * kMapTiltRad;
    samples.add(so3::exp(-epsilon) * own_up_L, R_W_L, 4e4);  // the tilt factor's (0.005 rad)^-2
  }
  return samples.mount();
}

TEST(TiltOffset, TheRigsTurnsTellTheMountFromTheMapsTilt) {
  std::vector<double> yaws;
  for (int k = 0; k < 72; ++k) yaws.push_back(k * 2.0 * M_PI / 72.0);
  const Vec3 mount = estimate(yaws);
  // The prior on the mount's part takes 1/11 of it (kMountPriorShare 0.1); the map's tilt goes to its own part.
  EXPECT_NEAR(mount.x(), kMountRad.x() / 1.1, 1e-4);
  EXPECT_NEAR(mount.y(), kMountRad.y() / 1.1, 1e-4);
  // An out-and-back route (two headings) tells them apart as well.
  std::vector<double> out_and_back(40, 0.0);
  out_and_back.insert(out_and_back.end(), 40, M_PI);
  EXPECT_LT((estimate(out_and_back) - kMountRad / 1.1).head<2>().norm(), 1e-4);
}

TEST(TiltOffset, WithoutTurnsTheMapsTiltKeepsIt) {
  const Vec3 mount = estimate(std::vector<double>(80, 0.3));
  EXPECT_LT(mount.norm(), 1e-5);  // the whole offset is left to the map's tilt, which the tilt factors level
  EXPECT_EQ(UpOffsetSamples().mount(), Vec3::Zero());
}

TEST(TiltOffset, ARigidMoveOfThePosesKeepsTheMapsTiltInItsFrame) {
  // GlobalPoseGraph::transform moves every pose: the map's tilt is then seen in the new frame, the mount's is not.
  // Poses heading 0 before the move and heading pi after it (in the old frame) tell the two apart only if the
  // samples before the move are carried into the new frame.
  const Mat3 R_new_old = so3::rot_z(1.2);
  const auto sample = [](UpOffsetSamples& samples, const Mat3& R_W_L, const Vec3& map_tilt_W) {
    const Vec3 epsilon = kMountRad + R_W_L.transpose() * map_tilt_W;
    samples.add(so3::exp(-epsilon) * (R_W_L.transpose() * Vec3::UnitZ()), R_W_L, 4e4);
  };
  UpOffsetSamples samples;
  for (int k = 0; k < 40; ++k) sample(samples, Mat3::Identity(), kMapTiltRad);
  samples.rotate_world(R_new_old);
  for (int k = 0; k < 40; ++k) sample(samples, R_new_old * so3::rot_z(M_PI), R_new_old * kMapTiltRad);
  EXPECT_LT((samples.mount() - kMountRad / 1.1).head<2>().norm(), 1e-4);
}

}  // namespace
}  // namespace vilslam::loop
