// The loop a scan-to-map registration makes after re-localizing (loop/registration_loop.h): from the nearest map
// key scan, measuring what the registration measured, nothing beyond the weak sigmas along what it left free.
#include <gtest/gtest.h>

#include <Eigen/Cholesky>

#include "loop/registration_loop.h"

namespace vilslam::loop {
namespace {

struct Map {
  std::vector<KeyFrame> key_frames;
  Trajectory poses;
};

// Map poses every 2 m along x; key frames on every other pose (0, 4, 8 m).
Map straight_map() {
  Map m;
  for (int i = 0; i < 5; ++i) m.poses.push_back({i * 100'000'000LL, SE3(so3::exp(Vec3(0, 0, 0.1 * i)), Vec3(2.0 * i, 0, 0))});
  for (std::size_t i = 0; i < 5; i += 2) {
    KeyFrame kf;
    kf.id = m.key_frames.size();
    kf.pose_index = i;
    m.key_frames.push_back(kf);
  }
  return m;
}

Mat6 strong_information() { return Mat6::Identity() * 1e6; }  // J^T J of a well-constrained registration

TEST(RegistrationLoop, FromTheNearestMapKeyScanToTheRegisteredPose) {
  const Map map = straight_map();
  const SE3 T_W_Lv(so3::exp(Vec3(0.01, 0, 0.3)), Vec3(4.6, 0.2, 0.1));  // nearest key scan: pose 2 at x = 4 m
  const auto loop = registration_loop(map.key_frames, map.poses, T_W_Lv, strong_information(), {}, 5.0, {});
  ASSERT_TRUE(loop.has_value());
  EXPECT_EQ(loop->map_pose_index, 2u);
  const SE3 T_W_Lv_again = map.poses[2].T_W_B * loop->T_Lu_Lv;
  EXPECT_LT((T_W_Lv_again.translation() - T_W_Lv.translation()).norm(), 1e-12);
  EXPECT_LT(so3::log(T_W_Lv_again.rotation().transpose() * T_W_Lv.rotation()).norm(), 1e-12);
  // Pose 1 (x = 2 m) is nearer but carries no key scan: never the anchor.
  const auto near_pose_1 = registration_loop(map.key_frames, map.poses, SE3(Mat3::Identity(), Vec3(2.9, 0, 0)),
                                             strong_information(), {}, 5.0, {});
  ASSERT_TRUE(near_pose_1.has_value());
  EXPECT_EQ(near_pose_1->map_pose_index, 2u);
}

TEST(RegistrationLoop, NoneWhenNoMapKeyScanIsWithinTheDistance) {
  const Map map = straight_map();
  EXPECT_FALSE(registration_loop(map.key_frames, map.poses, SE3(Mat3::Identity(), Vec3(20, 0, 0)), strong_information(),
                                 {}, 5.0, {})
                   .has_value());
  EXPECT_FALSE(registration_loop({}, map.poses, SE3(), strong_information(), {}, 5.0, {}).has_value());
}

TEST(RegistrationLoop, MeasuresOnlyWhatTheRegistrationMeasured) {
  const Map map = straight_map();
  const RegistrationLoopSigmas sigmas;  // point 5 cm, loop floor 2 cm / 0.002 rad, degenerate 0.1 m / 0.02 rad
  // A corridor: the registration left its axis (x) and the roll about it free.
  Vec6 axis = Vec6::Zero(), roll = Vec6::Zero();
  axis(0) = 1.0;
  roll(3) = 1.0;
  const auto loop = registration_loop(map.key_frames, map.poses, SE3(Mat3::Identity(), Vec3(4, 0, 0)),
                                      strong_information(), {axis, roll}, 5.0, sigmas);
  ASSERT_TRUE(loop.has_value());
  const Mat6& info = loop->information;
  // Free directions: the degenerate sigma and the floor in series, (0.1^2 + 0.02^2)^-1 = 96.15 m^-2.
  EXPECT_NEAR(info(0, 0), 1.0 / (0.1 * 0.1 + 0.02 * 0.02), 1e-6);
  EXPECT_NEAR(info(3, 3), 1.0 / (0.02 * 0.02 + 0.002 * 0.002), 1e-6);
  // Measured directions: 1e6 / 0.05^2 = 4e8 in series with the floor, so the floor's 2500 m^-2 (and 2.5e5 rad^-2).
  EXPECT_NEAR(info(1, 1), 1.0 / (1.0 / 4e8 + 0.02 * 0.02), 1e-6);
  EXPECT_NEAR(info(4, 4), 1.0 / (1.0 / 4e8 + 0.002 * 0.002), 1e-3);
  EXPECT_LT(info(0, 0), 0.05 * info(1, 1));
  // Full rank with two free directions, so the graph takes it (its factor needs a Cholesky factor).
  EXPECT_EQ(Eigen::LLT<Mat6>(info).info(), Eigen::Success);
  // Without free directions x is measured like y.
  const auto full = registration_loop(map.key_frames, map.poses, SE3(Mat3::Identity(), Vec3(4, 0, 0)),
                                      strong_information(), {}, 5.0, sigmas);
  EXPECT_NEAR(full->information(0, 0), full->information(1, 1), 1e-6);
}

}  // namespace
}  // namespace vilslam::loop
