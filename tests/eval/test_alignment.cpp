#include <gtest/gtest.h>

#include <random>

#include "eval/alignment.h"

namespace vilslam::eval {
namespace {

std::vector<Vec3> random_points(std::size_t n, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-20.0, 20.0);
  std::vector<Vec3> p;
  for (std::size_t i = 0; i < n; ++i) p.emplace_back(u(rng), u(rng), 0.2 * u(rng));
  return p;
}

std::vector<Vec3> transform(const std::vector<Vec3>& p, double scale, const SE3& T) {
  std::vector<Vec3> out;
  for (const Vec3& x : p) out.push_back(T.quat() * (scale * x) + T.translation());
  return out;
}

void expect_recovers(const Alignment& a, double scale, const SE3& T) {
  EXPECT_NEAR(a.scale, scale, 1e-10);
  EXPECT_LT((a.T_gt_est.translation() - T.translation()).norm(), 1e-9);
  EXPECT_LT(so3::log(a.T_gt_est.quat().conjugate() * T.quat()).norm(), 1e-10);
}

TEST(Alignment, Se3RecoversKnownTransformExactly) {
  const SE3 T(so3::exp_quat(Vec3(0.3, -0.2, 1.4)), Vec3(5, -3, 2));
  const auto x = random_points(50, 1);
  const Alignment a = align_positions(x, transform(x, 1.0, T), AlignMode::kSe3);
  EXPECT_EQ(a.mode, AlignMode::kSe3);
  expect_recovers(a, 1.0, T);
}

TEST(Alignment, Sim3RecoversKnownTransformAndScaleExactly) {
  const SE3 T(so3::exp_quat(Vec3(-1.0, 0.4, 2.5)), Vec3(-7, 1, 0.5));
  const auto x = random_points(50, 2);
  expect_recovers(align_positions(x, transform(x, 2.7, T), AlignMode::kSim3), 2.7, T);
  // se3 cannot explain a scale change: its residual is clearly non-zero.
  const auto y = transform(x, 2.7, T);
  const Alignment rigid = align_positions(x, y, AlignMode::kSe3);
  EXPECT_EQ(rigid.scale, 1.0);
  EXPECT_GT((rigid.T_gt_est * x[0] - y[0]).norm(), 1.0);
}

TEST(Alignment, PosYawRecoversYawAndTranslationExactly) {
  const SE3 T(so3::exp_quat(Vec3(0, 0, -2.2)), Vec3(3, 4, -1));
  const auto x = random_points(50, 3);
  const Alignment a = align_positions(x, transform(x, 1.0, T), AlignMode::kPosYaw);
  EXPECT_EQ(a.mode, AlignMode::kPosYaw);
  expect_recovers(a, 1.0, T);
}

TEST(Alignment, PosYawKeepsGravityDirectionWhenDataIsTilted) {
  const SE3 T(so3::exp_quat(Vec3(0.3, 0, 0.5)), Vec3(1, 2, 3));
  const auto x = random_points(50, 4);
  const Alignment a = align_positions(x, transform(x, 1.0, T), AlignMode::kPosYaw);
  EXPECT_LT((a.T_gt_est.rotation() * Vec3::UnitZ() - Vec3::UnitZ()).norm(), 1e-12);
}

TEST(Alignment, FirstNPosesAndApplication) {
  const SE3 T(so3::exp_quat(Vec3(0.1, 0.2, 0.3)), Vec3(1, 1, 1));
  const auto x = random_points(20, 5);
  auto y = transform(x, 1.0, T);
  for (std::size_t i = 10; i < y.size(); ++i) y[i] += Vec3(0, 0, 5);  // later poses disagree
  Trajectory est, gt;
  for (std::size_t i = 0; i < x.size(); ++i) {
    est.push_back({static_cast<TimeNs>(i), SE3(Quat::Identity(), x[i])});
    gt.push_back({static_cast<TimeNs>(i), SE3(T.quat(), y[i])});
  }
  const Alignment a = align_trajectories(est, gt, AlignMode::kSe3, 10);
  expect_recovers(a, 1.0, T);
  const Trajectory moved = apply_alignment(est, a);
  EXPECT_LT((moved[3].T_W_B.translation() - gt[3].T_W_B.translation()).norm(), 1e-9);
  EXPECT_LT(so3::log(moved[3].T_W_B.quat().conjugate() * gt[3].T_W_B.quat()).norm(), 1e-10);
  const Alignment all = align_trajectories(est, gt, AlignMode::kSe3, 0);
  EXPECT_GT((all.T_gt_est.translation() - T.translation()).norm(), 0.1);
}

TEST(Alignment, NoneIsIdentityAndNamesRoundTrip) {
  const auto x = random_points(5, 6);
  const Alignment a = align_positions(x, transform(x, 1.0, SE3(Quat::Identity(), Vec3(1, 0, 0))), AlignMode::kNone);
  EXPECT_EQ(a.T_gt_est.translation(), Vec3::Zero());
  for (const char* name : {"se3", "sim3", "posyaw", "none"}) EXPECT_EQ(align_mode_name(parse_align_mode(name)), name);
  EXPECT_THROW(parse_align_mode("sim2"), std::invalid_argument);
}

TEST(Alignment, DegenerateInputThrows) {
  const std::vector<Vec3> same(10, Vec3(1, 2, 3));
  EXPECT_THROW(align_positions(same, same, AlignMode::kSe3), std::invalid_argument);
  EXPECT_THROW(align_positions(same, same, AlignMode::kPosYaw), std::invalid_argument);
  EXPECT_THROW(align_positions(same, std::vector<Vec3>(3), AlignMode::kSe3), std::invalid_argument);
}

}  // namespace
}  // namespace vilslam::eval
