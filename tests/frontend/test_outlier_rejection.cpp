#include <gtest/gtest.h>

#include <random>

#include "frontend/outlier_rejection.h"
#include "synthetic_stereo.h"

namespace vilslam {
namespace {

std::vector<Vec3> random_scene(int count, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> x(-3, 3), y(-2, 2), z(2, 10);
  std::vector<Vec3> points;
  for (int i = 0; i < count; ++i) points.emplace_back(x(rng), y(rng), z(rng));
  return points;
}

TEST(OutlierRejection, TriangulationRecoversPoints) {
  const StereoRig rig = make_stereo_rig(test::pinhole_stereo_rig());
  for (const Vec3& p_C0 : random_scene(100, 1)) {
    Vec3 estimate;
    ASSERT_TRUE(triangulate_stereo(p_C0.hnormalized(), (rig.T_C1_C0 * p_C0).hnormalized(), rig.T_C1_C0, &estimate));
    EXPECT_LT((estimate - p_C0).norm(), 1e-9 * p_C0.norm());
  }
  Vec3 estimate;
  // Rays that only meet behind the cameras (negative disparity).
  EXPECT_FALSE(triangulate_stereo({0.0, 0.0}, {0.05, 0.0}, rig.T_C1_C0, &estimate));
}

TEST(OutlierRejection, StereoReprojectionErrorAveragesBothImages) {
  const StereoRig rig = make_stereo_rig(test::pinhole_stereo_rig());
  const Vec3 p_C0(0.3, -0.2, 4.0);
  Eigen::Vector2d left_px, right_px;
  ASSERT_TRUE(rig.cam0.project(p_C0, &left_px));
  ASSERT_TRUE(rig.cam1.project(rig.T_C1_C0 * p_C0, &right_px));
  EXPECT_NEAR(stereo_reprojection_error_px(rig, p_C0, left_px, right_px), 0, 1e-9);
  EXPECT_NEAR(stereo_reprojection_error_px(rig, p_C0, left_px + Eigen::Vector2d(3, 4), right_px), 2.5, 1e-9);
  EXPECT_TRUE(std::isinf(stereo_reprojection_error_px(rig, Vec3(0, 0, -1), left_px, right_px)));
}

TEST(OutlierRejection, PnpRansacRecoversMotionDespiteOutliersDeterministically) {
  const SE3 T_cur_prev(so3::exp(Vec3(0.02, -0.05, 0.01)), Vec3(0.10, -0.03, 0.05));
  const std::vector<Vec3> p_prev = random_scene(120, 2);
  std::mt19937 rng(3);
  std::normal_distribution<double> noise(0, 0.5 / 450);  // 0.5 px
  std::uniform_real_distribution<double> anywhere(-0.7, 0.7);
  std::vector<Eigen::Vector2d> xy_cur;
  for (std::size_t i = 0; i < p_prev.size(); ++i) {
    const bool outlier = i % 3 == 0;
    xy_cur.push_back(outlier ? Eigen::Vector2d(anywhere(rng), anywhere(rng))
                             : Eigen::Vector2d((T_cur_prev * p_prev[i]).hnormalized() +
                                               Eigen::Vector2d(noise(rng), noise(rng))));
  }
  const FrontendConfig config;
  const MotionEstimate a = estimate_motion_pnp(p_prev, xy_cur, 450, config);
  ASSERT_TRUE(a.valid);
  EXPECT_GE(a.inliers, 78);
  EXPECT_LE(a.inliers, 82);
  EXPECT_LT((a.T_C0cur_C0prev.translation() - T_cur_prev.translation()).norm(), 0.01);
  EXPECT_LT(so3::log(a.T_C0cur_C0prev.rotation().transpose() * T_cur_prev.rotation()).norm(), 2e-3);
  const MotionEstimate b = estimate_motion_pnp(p_prev, xy_cur, 450, config);
  EXPECT_EQ(a.inliers, b.inliers);
  EXPECT_EQ(a.T_C0cur_C0prev.matrix(), b.T_C0cur_C0prev.matrix());
  const std::vector<Vec3> few(p_prev.begin(), p_prev.begin() + config.pnp_min_points - 1);
  EXPECT_FALSE(estimate_motion_pnp(few, xy_cur, 450, config).valid);
}

}  // namespace
}  // namespace vilslam
