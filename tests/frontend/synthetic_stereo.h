#pragma once
// Test scenes with exact geometry: a textured plane seen by an undistorted pinhole stereo rig, rendered
// with the plane-induced homography (no simulator needed for the frontend's unit tests).
#include <opencv2/imgproc.hpp>

#include <random>

#include "common/calibration.h"
#include "common/lie.h"

namespace vilslam::test {

constexpr double kBaselineM = 0.11;

inline CameraIntrinsics pinhole_752x480() {
  CameraIntrinsics cam;
  cam.width_px = 752;
  cam.height_px = 480;
  cam.fx = cam.fy = 450;
  cam.cx = 375.5;
  cam.cy = 239.5;
  cam.rate_hz = 20;
  return cam;
}

// Left camera = I frame; the right camera sits kBaselineM along +x_C0.
inline RigCalibration pinhole_stereo_rig() {
  RigCalibration calib;
  calib.cam0 = calib.cam1 = pinhole_752x480();
  calib.T_I_C1 = SE3(Quat::Identity(), Vec3(kBaselineM, 0, 0));
  return calib;
}

// Random overlapping grey rectangles, slightly blurred: many corners, no repetitive structure.
inline cv::Mat random_texture(int width_px, int height_px, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> x(0, width_px - 1), y(0, height_px - 1), size(6, 40), grey(0, 255);
  cv::Mat texture(height_px, width_px, CV_8UC1, cv::Scalar(128));
  for (int i = 0; i < width_px * height_px / 300; ++i) {
    const cv::Point corner(x(rng), y(rng));
    cv::rectangle(texture, cv::Rect(corner, cv::Size(size(rng), size(rng))), cv::Scalar(grey(rng)), cv::FILLED);
  }
  cv::GaussianBlur(texture, texture, cv::Size(0, 0), 1.0);
  return texture;
}

// A textured plane: texture pixel (u, v) is the world point origin_W + scale (u e1_W + v e2_W).
struct TexturedPlane {
  cv::Mat texture;
  Vec3 origin_W;
  Vec3 e1_W, e2_W;  // orthonormal
  double meters_per_texel = 0.005;

  Vec3 normal_W() const { return e1_W.cross(e2_W); }

  // Intersection of the ray through normalized xy of camera pose T_W_C with the plane (point in C).
  Vec3 intersect(const SE3& T_W_C, const Eigen::Vector2d& xy) const {
    const Vec3 ray_W = T_W_C.rotation() * xy.homogeneous();
    const double s = normal_W().dot(origin_W - T_W_C.translation()) / normal_W().dot(ray_W);
    return s * Vec3(xy.x(), xy.y(), 1.0);
  }
};

// A plane facing the camera at depth_m, turned by yaw_rad about the vertical axis, centred on the axis.
inline TexturedPlane facing_plane(double depth_m, double yaw_rad, unsigned seed) {
  TexturedPlane plane;
  plane.texture = random_texture(1400, 1000, seed);
  const Mat3 R = so3::exp(Vec3(0, yaw_rad, 0));
  plane.e1_W = R * Vec3::UnitX();
  plane.e2_W = R * Vec3::UnitY();
  const double half_w = 0.5 * plane.texture.cols * plane.meters_per_texel;
  const double half_h = 0.5 * plane.texture.rows * plane.meters_per_texel;
  plane.origin_W = Vec3(0, 0, depth_m) - half_w * plane.e1_W - half_h * plane.e2_W;
  return plane;
}

// Renders the plane into a pinhole camera at T_W_C: pixel = K (R_C_W p_W + t_C_W), p_W linear in (u, v, 1).
inline cv::Mat render_plane(const TexturedPlane& plane, const CameraIntrinsics& cam, const SE3& T_W_C) {
  const SE3 T_C_W = T_W_C.inverse();
  Mat3 M;
  M.col(0) = T_C_W.rotation() * plane.e1_W * plane.meters_per_texel;
  M.col(1) = T_C_W.rotation() * plane.e2_W * plane.meters_per_texel;
  M.col(2) = T_C_W * plane.origin_W;
  Mat3 K;
  K << cam.fx, 0, cam.cx, 0, cam.fy, cam.cy, 0, 0, 1;
  const Mat3 H = K * M;
  cv::Mat H_cv(3, 3, CV_64F);
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) H_cv.at<double>(r, c) = H(r, c);
  cv::Mat image;
  cv::warpPerspective(plane.texture, image, H_cv, cv::Size(cam.width_px, cam.height_px), cv::INTER_LINEAR,
                      cv::BORDER_CONSTANT, cv::Scalar(0));
  return image;
}

}  // namespace vilslam::test
