// EPnP information from reprojection Jacobians, its move into the key scans' frames, and the fusion of two
// estimates, and the loop factor's information: each checked against finite differences or a case with a
// known answer.
#include <gtest/gtest.h>

#include <random>

#include "loop/constraint_fusion.h"
#include "loop/loop_constraint.h"

namespace vilslam::loop {
namespace {

constexpr double kFocalPx = 450.0;

SE3 some_pose(double a) { return SE3(so3::exp(Vec3(0.1 * a, -0.2, 0.05)), Vec3(0.3, -0.1 * a, 0.5)); }

struct Scene {
  SE3 T_C0cur_C0prev = some_pose(1.0);
  std::vector<Vec3> p_C0prev;
  std::vector<Eigen::Vector2d> xy_cur;
};

// 40 points 2-12 m in front of the previous camera, observed exactly by the current one; the last
// observation is moved 20 px (an outlier).
Scene make_scene() {
  Scene s;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> lateral(-3.0, 3.0), depth(2.0, 12.0);
  for (int i = 0; i < 40; ++i) {
    const Vec3 p(lateral(rng), lateral(rng), depth(rng));
    const Vec3 p_cur = s.T_C0cur_C0prev * p;
    if (p_cur.z() <= 0.5) continue;
    s.p_C0prev.push_back(p);
    s.xy_cur.push_back(p_cur.head<2>() / p_cur.z());
  }
  s.xy_cur.back().x() += 20.0 / kFocalPx;
  return s;
}

Eigen::Vector2d pixel(const SE3& T, const Vec3& p) {
  const Vec3 q = T * p;
  return kFocalPx * q.head<2>() / q.z();
}

TEST(ConstraintFusion, PnpInformationIsJtJOfTheInliersReprojectionJacobians) {
  const Scene s = make_scene();
  const double sigma_px = 2.0;
  const Mat6 info = pnp_information(s.T_C0cur_C0prev, s.p_C0prev, s.xy_cur, kFocalPx, 3.0, sigma_px);
  Mat6 numeric = Mat6::Zero();
  constexpr double kH = 1e-6;
  for (std::size_t i = 0; i + 1 < s.p_C0prev.size(); ++i) {  // the outlier is left out
    Eigen::Matrix<double, 2, 6> J;
    for (int k = 0; k < 6; ++k) {
      Vec6 d = Vec6::Zero();
      d[k] = kH;
      J.col(k) = (pixel(s.T_C0cur_C0prev * SE3::exp(d), s.p_C0prev[i]) -
                  pixel(s.T_C0cur_C0prev * SE3::exp(-d), s.p_C0prev[i])) / (2.0 * kH);
    }
    numeric += J.transpose() * J / (sigma_px * sigma_px);
  }
  EXPECT_LT((info - numeric).norm(), 1e-6 * numeric.norm());
  // With the outlier inside the gate it counts too.
  const Mat6 with_outlier = pnp_information(s.T_C0cur_C0prev, s.p_C0prev, s.xy_cur, kFocalPx, 25.0, sigma_px);
  EXPECT_GT((with_outlier - numeric).norm(), 1e-3 * numeric.norm());
}

// A perturbation d of T_C0v_C0u moves T_Lu_Lv by eps; the two quadratic forms must agree: d^T I d = eps^T I_L eps.
TEST(ConstraintFusion, InformationFollowsThePerturbationIntoTheLidarFrames) {
  const SE3 T_C0v_C0u = some_pose(1.0), T_Lu_C0u = some_pose(-2.0), T_Lv_C0v = some_pose(3.0);
  Mat6 A = Mat6::Random();
  const Mat6 info = A * A.transpose() + Mat6::Identity();
  const Mat6 info_L = information_in_lidar_frames(info, T_C0v_C0u, T_Lv_C0v);
  const SE3 T_Lu_Lv = lidar_constraint_from_camera(T_C0v_C0u, T_Lu_C0u, T_Lv_C0v);
  std::mt19937 rng(3);
  std::normal_distribution<double> n(0.0, 1e-5);
  for (int trial = 0; trial < 5; ++trial) {
    Vec6 d;
    for (int k = 0; k < 6; ++k) d[k] = n(rng);
    const SE3 moved = lidar_constraint_from_camera(T_C0v_C0u * SE3::exp(d), T_Lu_C0u, T_Lv_C0v);
    const Vec6 eps = (T_Lu_Lv.inverse() * moved).log();
    const double form = d.dot(info * d);
    EXPECT_NEAR(eps.dot(info_L * eps), form, 1e-4 * form);
  }
}

TEST(ConstraintFusion, EachDirectionComesFromTheEstimateThatKnowsIt) {
  const SE3 T_b = some_pose(0.5);
  const Vec6 offset = (Vec6() << 0.05, -0.03, 0.02, 0.01, -0.02, 0.005).finished();
  const SE3 T_a = T_b * SE3::exp(offset);
  // a knows x translation and roll 1e6 times better than b; b knows everything else 1e6 times better.
  Vec6 strong_a = Vec6::Constant(1.0), strong_b = Vec6::Constant(1e6);
  strong_a[0] = strong_a[3] = 1e6;
  strong_b[0] = strong_b[3] = 1.0;
  const SE3 fused = fuse_estimates(T_a, strong_a.asDiagonal(), T_b, strong_b.asDiagonal());
  const Vec6 fused_in_b = (T_b.inverse() * fused).log();
  for (int k = 0; k < 6; ++k) {
    const double expected = (k == 0 || k == 3) ? offset[k] : 0.0;
    EXPECT_NEAR(fused_in_b[k], expected, 1e-5 + 1e-2 * std::abs(offset[k])) << k;
  }
  // Equal information: half way.
  const SE3 half = fuse_estimates(T_a, Mat6::Identity(), T_b, Mat6::Identity());
  EXPECT_LT(((T_b.inverse() * half).log() - 0.5 * offset).norm(), 1e-12);
}

// The loop factor's information: the estimate's covariance plus the floor's, also where the estimate knows nothing.
TEST(ConstraintFusion, InformationWithFloorAddsTheCovariances) {
  Vec6 floor_diagonal, estimate_diagonal;
  floor_diagonal << 2500, 2500, 2500, 250000, 250000, 250000;  // 2 cm, 0.002 rad
  estimate_diagonal << 1e8, 100, 0, 1e9, 40000, 0;            // 0.1 mm, 10 cm, nothing, ...
  const Mat6 F = floor_diagonal.asDiagonal();
  const Mat6 diagonal = information_with_floor(estimate_diagonal.asDiagonal(), F);
  for (int k = 0; k < 6; ++k) {
    const double expected =
        estimate_diagonal[k] > 0 ? 1.0 / (1.0 / estimate_diagonal[k] + 1.0 / floor_diagonal[k]) : 0.0;
    EXPECT_NEAR(diagonal(k, k), expected, 1e-9 * floor_diagonal[k]) << k;
  }
  EXPECT_LT((diagonal - Mat6(diagonal.diagonal().asDiagonal())).norm(), 1e-6);
  // A full estimate information: (A^-1 + F^-1)^-1, symmetric.
  std::mt19937 rng(3);
  std::normal_distribution<double> normal(0.0, 1.0);
  Mat6 B;
  for (int i = 0; i < 36; ++i) B(i / 6, i % 6) = normal(rng);
  const Mat6 A = 1000.0 * (B * B.transpose() + Mat6::Identity());
  const Mat6 expected = (A.inverse() + F.inverse()).inverse();
  const Mat6 full = information_with_floor(A, F);
  EXPECT_LT((full - expected).norm(), 1e-9 * expected.norm());
  EXPECT_EQ(full, full.transpose());
}

}  // namespace
}  // namespace vilslam::loop
