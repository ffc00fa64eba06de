// When the VIO declares itself lost (vio/loss_check.h): each criterion alone, and the streak of rejected vision.
#include <gtest/gtest.h>

#include <limits>

#include "vio/loss_check.h"

namespace vilslam {
namespace {

NavState moving_state() {
  NavState x;
  x.v_W_m_s = Vec3(1.2, 0.0, 0.0);
  x.bias_gyro_rad_s = Vec3(0.002, -0.001, 0.0);
  x.bias_accel_m_s2 = Vec3(0.05, 0.0, -0.02);
  return x;
}

TEST(VioLossCheck, ANormalStateIsNotLost) {
  VioLossCheck check({});
  for (int k = 0; k < 50; ++k) EXPECT_EQ(check.check(moving_state(), Mat15::Identity(), 200, 180, 180.0), VioLoss::kNone);
}

// The cost of a consistent landmark grows with its observations: a 20-state window's landmarks may cost twice
// a 10-state window's before they count as inconsistent (a realistic tunnel run with 20 states was declared lost
// 12 times with the unscaled threshold, never with it doubled).
TEST(VioLossCheck, TheCostThresholdScalesWithTheWindow) {
  VioLossConfig config;
  config.recent_states = config.inconsistent_states = 1;
  const double cost = 25.0 * 180;  // 25 per landmark: over 15, under 30
  EXPECT_EQ(VioLossCheck(config, 10).check(moving_state(), Mat15::Identity(), 200, 180, cost), VioLoss::kInconsistent);
  EXPECT_EQ(VioLossCheck(config, 20).check(moving_state(), Mat15::Identity(), 200, 180, cost), VioLoss::kNone);
  EXPECT_EQ(VioLossCheck(config, 20).check(moving_state(), Mat15::Identity(), 200, 180, 2.2 * cost),
            VioLoss::kInconsistent);
}

TEST(VioLossCheck, NotFiniteSpeedAndBiasAreLostAtOnce) {
  VioLossCheck check({});
  NavState x = moving_state();
  x.p_W_I.x() = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(check.check(x, Mat15::Identity(), 200, 180, 180.0), VioLoss::kNotFinite);
  Mat15 cov = Mat15::Identity();
  cov(3, 3) = std::numeric_limits<double>::infinity();
  EXPECT_EQ(check.check(moving_state(), cov, 200, 180, 180.0), VioLoss::kNotFinite);
  x = moving_state();
  x.v_W_m_s = Vec3(25.0, 20.0, 0.0);  // 32 m/s
  EXPECT_EQ(check.check(x, Mat15::Identity(), 200, 180, 180.0), VioLoss::kSpeed);
  x = moving_state();
  x.bias_accel_m_s2 = Vec3(0.0, 2.5, 0.0);
  EXPECT_EQ(check.check(x, Mat15::Identity(), 200, 180, 180.0), VioLoss::kBias);
  x = moving_state();
  x.bias_gyro_rad_s = Vec3(0.0, 0.0, -0.4);
  EXPECT_EQ(check.check(x, Mat15::Identity(), 200, 180, 180.0), VioLoss::kBias);
  VioLossConfig off;
  off.enabled = false;
  EXPECT_EQ(VioLossCheck(off).check(x, Mat15::Identity(), 200, 180, 180.0), VioLoss::kNone);
}

TEST(VioLossCheck, SixInconsistentStatesOfTheLastTenAreLost) {
  VioLossCheck check({});
  const Mat15 cov = Mat15::Identity();
  const auto consistent = [&] { return check.check(moving_state(), cov, 200, 150, 150.0); };
  // Five of ten: landmarks under a tenth of the matches, or a cost per landmark over 15; never six of ten.
  for (int round = 0; round < 3; ++round) {
    for (int k = 0; k < 3; ++k) EXPECT_EQ(check.check(moving_state(), cov, 200, 5, 5.0), VioLoss::kNone);
    for (int k = 0; k < 2; ++k) EXPECT_EQ(check.check(moving_state(), cov, 200, 100, 1600.0), VioLoss::kNone);
    for (int k = 0; k < 5; ++k) EXPECT_EQ(consistent(), VioLoss::kNone);
  }
  // Frames with too few matches to tell count as consistent.
  for (int k = 0; k < 5; ++k) EXPECT_EQ(check.check(moving_state(), cov, 200, 0, 0.0), VioLoss::kNone);
  for (int k = 0; k < 5; ++k) EXPECT_EQ(check.check(moving_state(), cov, 10, 0, 0.0), VioLoss::kNone);
  // Five inconsistent, then a sixth within the last ten: lost.
  for (int k = 0; k < 5; ++k) EXPECT_EQ(check.check(moving_state(), cov, 200, 0, 0.0), VioLoss::kNone);
  EXPECT_EQ(consistent(), VioLoss::kNone);
  EXPECT_EQ(check.check(moving_state(), cov, 200, 100, 1600.0), VioLoss::kInconsistent);
  check.reset();
  EXPECT_EQ(check.check(moving_state(), cov, 200, 0, 0.0), VioLoss::kNone);
  EXPECT_EQ(vio_loss_name(VioLoss::kInconsistent), "lost_inconsistent");
}

}  // namespace
}  // namespace vilslam
