#include <gtest/gtest.h>
#include <opencv2/calib3d.hpp>

#include <cmath>
#include <random>

#include "common/error.h"
#include "euroc_camera.h"
#include "frontend/camera_model.h"

namespace vilslam {
namespace {

// TUM-VI-like fisheye (Kalibr equidistant).
CameraIntrinsics fisheye_cam() {
  CameraIntrinsics cam;
  cam.width_px = 512;
  cam.height_px = 512;
  cam.fx = 190.978;
  cam.fy = 190.973;
  cam.cx = 254.932;
  cam.cy = 256.897;
  cam.distortion = DistortionModel::kEquidistant;
  cam.distortion_coeffs = {0.00348238, 0.000715034, -0.00205323, 0.000202937};
  return cam;
}

cv::Mat camera_matrix(const CameraIntrinsics& cam) {
  return (cv::Mat_<double>(3, 3) << cam.fx, 0, cam.cx, 0, cam.fy, cam.cy, 0, 0, 1);
}

// Every 16th pixel of the image, borders included; for the fisheye only pixels less than ~75 degrees off
// the axis (beyond 90 degrees there are no normalized coordinates).
bool usable(const CameraIntrinsics& cam, double u, double v) {
  return cam.distortion != DistortionModel::kEquidistant || std::hypot(u - cam.cx, v - cam.cy) < 1.3 * cam.fx;
}

std::vector<cv::Point2d> pixel_grid(const CameraIntrinsics& cam) {
  std::vector<cv::Point2d> px;
  for (int v = 0; v < cam.height_px; v += 16)
    for (int u = 0; u < cam.width_px; u += 16)
      if (usable(cam, u, v)) px.emplace_back(u, v);
  if (usable(cam, cam.width_px - 1, cam.height_px - 1)) px.emplace_back(cam.width_px - 1, cam.height_px - 1);
  return px;
}

std::vector<Vec3> random_points_in_view(const CameraModel& model, int count, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0, model.intrinsics().width_px - 1), v(0, model.intrinsics().height_px - 1),
      depth(0.5, 20);
  std::vector<Vec3> points;
  while (static_cast<int>(points.size()) < count) {
    const Eigen::Vector2d px(u(rng), v(rng));
    const double z = depth(rng);
    if (usable(model.intrinsics(), px.x(), px.y())) points.push_back(model.unproject(px) * z);
  }
  return points;
}

TEST(CameraModel, RadTanUndistortMatchesOpenCv) {
  const CameraIntrinsics cam = test::euroc_cam0();
  const CameraModel model(cam);
  const std::vector<cv::Point2d> px = pixel_grid(cam);
  std::vector<cv::Point2d> xy_cv;
  cv::undistortPoints(px, xy_cv, camera_matrix(cam), cam.distortion_coeffs, cv::noArray(), cv::noArray(),
                      cv::TermCriteria(cv::TermCriteria::COUNT | cv::TermCriteria::EPS, 200, 1e-15));
  double worst = 0;
  for (std::size_t i = 0; i < px.size(); ++i) {
    const Eigen::Vector2d xy = model.pixel_to_normalized({px[i].x, px[i].y});
    worst = std::max(worst, (xy - Eigen::Vector2d(xy_cv[i].x, xy_cv[i].y)).norm() * cam.fx);
  }
  EXPECT_LT(worst, 1e-3);  // pixels
}

TEST(CameraModel, RadTanProjectMatchesOpenCv) {
  const CameraIntrinsics cam = test::euroc_cam0();
  const CameraModel model(cam);
  const std::vector<Vec3> points = random_points_in_view(model, 300, 3);
  std::vector<cv::Point3d> object;
  for (const Vec3& p : points) object.emplace_back(p.x(), p.y(), p.z());
  std::vector<cv::Point2d> px_cv;
  cv::projectPoints(object, cv::Vec3d(0, 0, 0), cv::Vec3d(0, 0, 0), camera_matrix(cam), cam.distortion_coeffs, px_cv);
  for (std::size_t i = 0; i < points.size(); ++i) {
    Eigen::Vector2d px;
    ASSERT_TRUE(model.project(points[i], &px));
    EXPECT_LT((px - Eigen::Vector2d(px_cv[i].x, px_cv[i].y)).norm(), 1e-9);
  }
}

TEST(CameraModel, EquidistantMatchesOpenCvFisheye) {
  const CameraIntrinsics cam = fisheye_cam();
  const CameraModel model(cam);
  const std::vector<cv::Point2d> px = pixel_grid(cam);
  std::vector<cv::Point2d> xy_cv;
  cv::fisheye::undistortPoints(px, xy_cv, camera_matrix(cam), cam.distortion_coeffs, cv::noArray(), cv::noArray(),
                               cv::TermCriteria(cv::TermCriteria::COUNT | cv::TermCriteria::EPS, 200, 1e-15));
  for (std::size_t i = 0; i < px.size(); ++i) {
    const Eigen::Vector2d xy = model.pixel_to_normalized({px[i].x, px[i].y});
    EXPECT_LT((xy - Eigen::Vector2d(xy_cv[i].x, xy_cv[i].y)).norm(), 1e-7 * (1 + xy.squaredNorm())) << i;
  }
  const std::vector<Vec3> points = random_points_in_view(model, 300, 4);
  std::vector<cv::Point3d> object;
  for (const Vec3& p : points) object.emplace_back(p.x(), p.y(), p.z());
  std::vector<cv::Point2d> px_cv;
  cv::fisheye::projectPoints(object, px_cv, cv::Vec3d(0, 0, 0), cv::Vec3d(0, 0, 0), camera_matrix(cam),
                             cam.distortion_coeffs);
  for (std::size_t i = 0; i < points.size(); ++i) {
    Eigen::Vector2d projected;
    ASSERT_TRUE(model.project(points[i], &projected));
    EXPECT_LT((projected - Eigen::Vector2d(px_cv[i].x, px_cv[i].y)).norm(), 1e-8);
  }
}

TEST(CameraModel, PixelRoundTripBothModels) {
  for (const CameraIntrinsics& cam : {test::euroc_cam0(), fisheye_cam()}) {
    const CameraModel model(cam);
    for (const cv::Point2d& p : pixel_grid(cam)) {
      const Eigen::Vector2d px(p.x, p.y);
      EXPECT_LT((model.normalized_to_pixel(model.pixel_to_normalized(px)) - px).norm(), 1e-9);
    }
  }
}

TEST(CameraModel, ProjectionJacobianMatchesNumeric) {
  for (const CameraIntrinsics& cam : {test::euroc_cam0(), fisheye_cam()}) {
    const CameraModel model(cam);
    for (const Vec3& p : random_points_in_view(model, 50, 5)) {
      Eigen::Vector2d px;
      Eigen::Matrix<double, 2, 3> J;
      ASSERT_TRUE(model.project(p, &px, &J));
      const double h = 1e-6;
      for (int k = 0; k < 3; ++k) {
        Eigen::Vector2d plus, minus;
        model.project(p + h * Vec3::Unit(k), &plus);
        model.project(p - h * Vec3::Unit(k), &minus);
        EXPECT_LT((J.col(k) - (plus - minus) / (2 * h)).norm(), 1e-5 * (1 + J.col(k).norm()));
      }
    }
  }
}

TEST(CameraModel, RejectsBehindCameraAndBadCoefficients) {
  const CameraModel model(test::euroc_cam0());
  Eigen::Vector2d px;
  EXPECT_FALSE(model.project(Vec3(0.1, 0.2, -1), &px));
  CameraIntrinsics bad = test::euroc_cam0();
  bad.distortion_coeffs.pop_back();
  EXPECT_THROW(CameraModel{bad}, InputError);
}

}  // namespace
}  // namespace vilslam
