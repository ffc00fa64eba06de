// The renderer's camera model against OpenCV's implementations of the same distortion models.
#include <gtest/gtest.h>

#include <opencv2/calib3d.hpp>

#include "common/error.h"
#include "sim/camera_rays.h"
#include "euroc_camera.h"

namespace vilslam::sim {
namespace {

// EuRoC's cam0 with the given distortion model (equidistant: TUM-VI-like coefficients).
CameraIntrinsics euroc_like(DistortionModel model) {
  CameraIntrinsics c = test::euroc_cam0();
  if (model == DistortionModel::kRadTan) return c;
  c.distortion = model;
  c.distortion_coeffs = {-0.0111, 0.0342, -0.0454, 0.0186};
  return c;
}

std::vector<cv::Point3d> grid_points() {
  std::vector<cv::Point3d> pts;
  for (double x = -0.7; x <= 0.7; x += 0.1)
    for (double y = -0.45; y <= 0.45; y += 0.09) pts.emplace_back(x * 3, y * 3, 3.0);
  return pts;
}

TEST(CameraRays, ProjectionMatchesOpenCV) {
  const std::vector<cv::Point3d> pts = grid_points();
  for (DistortionModel model : {DistortionModel::kRadTan, DistortionModel::kEquidistant}) {
    const CameraIntrinsics c = euroc_like(model);
    const cv::Matx33d K(c.fx, 0, c.cx, 0, c.fy, c.cy, 0, 0, 1);
    std::vector<cv::Point2d> ref;
    if (model == DistortionModel::kRadTan) {
      cv::projectPoints(pts, cv::Vec3d(0, 0, 0), cv::Vec3d(0, 0, 0), K, c.distortion_coeffs, ref);
    } else {
      cv::fisheye::projectPoints(pts, ref, cv::Vec3d(0, 0, 0), cv::Vec3d(0, 0, 0), K, c.distortion_coeffs);
    }
    for (std::size_t i = 0; i < pts.size(); ++i) {
      const Eigen::Vector2d px = project(c, Vec3(pts[i].x, pts[i].y, pts[i].z));
      EXPECT_NEAR(px.x(), ref[i].x, 1e-6);
      EXPECT_NEAR(px.y(), ref[i].y, 1e-6);
    }
  }
}

TEST(CameraRays, RayTableReprojectsToPixelCentres) {
  for (DistortionModel model : {DistortionModel::kNone, DistortionModel::kRadTan, DistortionModel::kEquidistant}) {
    const CameraIntrinsics c = euroc_like(model);
    const auto table = ray_table(c);
    ASSERT_EQ(table->dir_C.size(), 752u * 480u);
    double worst = 0;
    for (int r = 0; r < c.height_px; r += 7) {
      for (int col = 0; col < c.width_px; col += 5) {
        const Eigen::Vector3f& d = table->dir_C[static_cast<std::size_t>(r) * c.width_px + col];
        EXPECT_NEAR(d.norm(), 1.0f, 1e-6f);
        worst = std::max(worst, (project(c, d.cast<double>() * 4.0) - Eigen::Vector2d(col, r)).norm());
      }
    }
    EXPECT_LT(worst, 1e-3) << "model " << static_cast<int>(model);
    // The angle of one pixel is about 1 / f at the centre.
    const float centre = table->pixel_angle_rad[248 * 752 + 367];
    EXPECT_NEAR(centre, 1 / c.fx, 0.05 / c.fx);
  }
  EXPECT_EQ(ray_table(euroc_like(DistortionModel::kRadTan)).get(), ray_table(euroc_like(DistortionModel::kRadTan)).get());
}

TEST(CameraRays, BadIntrinsicsThrowInputError) {
  CameraIntrinsics c = euroc_like(DistortionModel::kRadTan);
  c.distortion_coeffs.pop_back();
  EXPECT_THROW(ray_table(c), InputError);
  c = euroc_like(DistortionModel::kNone);
  c.fx = -1;
  EXPECT_THROW(ray_table(c), InputError);
  c = euroc_like(DistortionModel::kNone);
  c.width_px = 0;
  EXPECT_THROW(ray_table(c), InputError);
  c = euroc_like(DistortionModel::kEquidistant);
  c.distortion_coeffs[1] = std::nan("");
  EXPECT_THROW(ray_table(c), InputError);
}

TEST(CameraRays, LookingPoseAxes) {
  const Vec3 forward(0.6, -0.8, 0.0);
  const SE3 T_W_C = camera_pose_looking(Vec3(1, 2, 1.5), forward);
  const Mat3 R = T_W_C.rotation();
  EXPECT_NEAR((R.col(2) - forward).norm(), 0, 1e-12);
  EXPECT_NEAR(R.col(1).z(), -1, 1e-12) << "y_C points down";
  EXPECT_NEAR(R.determinant(), 1, 1e-12);
  // A point ahead and to the right of the camera has positive x_C.
  const Vec3 right_W = forward.cross(Vec3::UnitZ());
  EXPECT_GT((T_W_C.inverse() * (T_W_C.translation() + 3 * forward + right_W)).x(), 0);
}

}  // namespace
}  // namespace vilslam::sim
