// The renderer draws the world where the calibration projects it: depth and image content checked
// against OpenCV's distortion models, stereo disparity against f b / z; noise, gain, blur, determinism.
#include <gtest/gtest.h>

#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>

#include "common/error.h"
#include "sim/camera_rays.h"
#include "sim/camera_render.h"
#include "sim/scenario_figures.h"
#include "sim/sim_config.h"
#include "euroc_camera.h"

namespace vilslam::sim {
namespace {

const World& highbay() {
  static const World world = World::generate(Scenario::kHighbay, 3);
  return world;
}

RenderOptions noiseless() {
  RenderOptions o;
  o.noise_sigma_grey = 0;
  return o;
}

std::function<SE3(TimeNs)> fixed(const SE3& T) {
  return [T](TimeNs) { return T; };
}

// Undistorted normalized coordinates of distorted pixels, by OpenCV.
std::vector<cv::Point2d> opencv_undistort(const CameraIntrinsics& c, const std::vector<cv::Point2d>& px) {
  std::vector<cv::Point2d> xy;
  const cv::Matx33d K(c.fx, 0, c.cx, 0, c.fy, c.cy, 0, 0, 1);
  cv::undistortPoints(px, xy, K, c.distortion_coeffs, cv::noArray(), cv::noArray(),
                      cv::TermCriteria(cv::TermCriteria::COUNT | cv::TermCriteria::EPS, 100, 1e-12));
  return xy;
}

TEST(CameraRender, DepthMatchesRaysOfTheCalibration) {
  const World& world = highbay();
  const CameraIntrinsics cam = test::euroc_cam0();
  const SE3 T_W_C = route_camera_pose(world.route_W(), 0);
  cv::Mat depth;
  render_image(world, cam, fixed(T_W_C), 0, noiseless(), &depth);
  std::vector<cv::Point2d> px;
  for (int r = 5; r < cam.height_px; r += 23)
    for (int c = 5; c < cam.width_px; c += 31) px.emplace_back(c, r);
  const std::vector<cv::Point2d> xy = opencv_undistort(cam, px);
  int checked = 0, agree = 0;
  for (std::size_t i = 0; i < px.size(); ++i) {
    const float z = depth.at<float>(static_cast<int>(px[i].y), static_cast<int>(px[i].x));
    if (z <= 0) continue;
    // The world point the renderer drew at this pixel, by OpenCV's model, projects back onto it...
    const Vec3 p_C(xy[i].x * z, xy[i].y * z, z);
    EXPECT_LT((project(cam, p_C) - Eigen::Vector2d(px[i].x, px[i].y)).norm(), 0.5);
    // ...and lies on the world's surface along that ray.
    const Vec3 ray_W = T_W_C.rotation() * p_C.normalized();
    const auto hit = world.raycast(T_W_C.translation(), ray_W, 1e3);
    ASSERT_TRUE(hit.has_value());
    ++checked;
    agree += std::abs(hit->range_m - p_C.norm()) < 1e-3 * p_C.norm() + 1e-3;
  }
  ASSERT_GT(checked, 100);
  EXPECT_GE(agree, checked * 98 / 100);
}

// Sub-pixel shift of each of 3 x 3 central patches between two images (phase correlation).
std::vector<cv::Point2d> patch_shifts(const cv::Mat& a, const cv::Mat& b) {
  std::vector<cv::Point2d> shifts;
  const int size = 96;
  for (int j = -1; j <= 1; ++j) {
    for (int i = -1; i <= 1; ++i) {
      const cv::Rect roi(a.cols / 2 + i * 220 - size / 2, a.rows / 2 + j * 140 - size / 2, size, size);
      cv::Mat pa, pb;
      a(roi).convertTo(pa, CV_64F);
      b(roi).convertTo(pb, CV_64F);
      double response = 0;
      shifts.push_back(cv::phaseCorrelate(pa, pb, cv::noArray(), &response));
    }
  }
  return shifts;
}

TEST(CameraRender, DistortedImageContentLandsWhereTheCalibrationProjectsIt) {
  const World& world = highbay();
  const CameraIntrinsics distorted = test::euroc_cam0();
  // Reference: an undistorted pinhole camera with a wider field of view at the same pose.
  CameraIntrinsics pinhole = default_camera();
  pinhole.width_px = 1100;
  pinhole.height_px = 760;
  pinhole.cx = 549.5;
  pinhole.cy = 379.5;
  const SE3 T_W_C = route_camera_pose(world.route_W(), 2);
  const cv::Mat image = render_image(world, distorted, fixed(T_W_C), 0, noiseless());
  const cv::Mat reference = render_image(world, pinhole, fixed(T_W_C), 0, noiseless());
  // Warp the pinhole image into the distorted camera with OpenCV's model.
  std::vector<cv::Point2d> px;
  for (int r = 0; r < distorted.height_px; ++r)
    for (int c = 0; c < distorted.width_px; ++c) px.emplace_back(c, r);
  const std::vector<cv::Point2d> xy = opencv_undistort(distorted, px);
  cv::Mat map_x(image.size(), CV_32F), map_y(image.size(), CV_32F);
  for (std::size_t i = 0; i < px.size(); ++i) {
    map_x.at<float>(static_cast<int>(px[i].y), static_cast<int>(px[i].x)) = static_cast<float>(pinhole.fx * xy[i].x + pinhole.cx);
    map_y.at<float>(static_cast<int>(px[i].y), static_cast<int>(px[i].x)) = static_cast<float>(pinhole.fy * xy[i].y + pinhole.cy);
  }
  cv::Mat warped;
  cv::remap(reference, warped, map_x, map_y, cv::INTER_LINEAR, cv::BORDER_REPLICATE);
  for (const cv::Point2d& s : patch_shifts(image, warped)) {
    EXPECT_LT(std::hypot(s.x, s.y), 0.5) << "patch shift " << s;
  }
}

// |measured - f b / z| of textured windows without depth edges: SSD block matching along the row with a
// parabola through the best integer disparity.
void stereo_errors(const cv::Mat& left, const cv::Mat& right, const cv::Mat& depth, double fx, double baseline_m,
                   std::vector<double>& errors) {
  cv::Mat lf, rf;
  left.convertTo(lf, CV_32F);
  right.convertTo(rf, CV_32F);
  const int half = 7;
  for (int r = 40; r < left.rows - 40; r += 12) {
    for (int c = 120; c < left.cols - 40; c += 12) {
      const cv::Rect win(c - half, r - half, 2 * half + 1, 2 * half + 1);
      double z_min, z_max;
      cv::minMaxLoc(depth(win), &z_min, &z_max);
      cv::Scalar mean, sd;
      cv::meanStdDev(lf(win), mean, sd);
      if (z_min <= 0 || z_max > 1.03 * z_min || sd[0] < 8) continue;
      const double predicted = fx * baseline_m / depth.at<float>(r, c);
      const int max_d = std::min(c - half - 1, static_cast<int>(predicted) + 6);
      if (predicted > max_d - 2) continue;
      std::vector<double> ssd;
      for (int d = 0; d <= max_d; ++d) ssd.push_back(cv::norm(lf(win), rf(win - cv::Point(d, 0)), cv::NORM_L2SQR));
      const int best = static_cast<int>(std::min_element(ssd.begin(), ssd.end()) - ssd.begin());
      if (best == 0 || best == max_d) continue;
      const double den = ssd[best - 1] - 2 * ssd[best] + ssd[best + 1];
      const double d = best + (den > 0 ? 0.5 * (ssd[best - 1] - ssd[best + 1]) / den : 0.0);
      errors.push_back(std::abs(d - predicted));
    }
  }
}

TEST(CameraRender, StereoDisparityMatchesDepth) {
  const World& world = highbay();
  const CameraIntrinsics cam = default_camera();
  const double baseline_m = 0.3;
  std::vector<double> errors;
  for (std::size_t k = 0; k < world.route_W().size() && errors.size() < 200; k += 5) {
    const SE3 T_W_C0 = route_camera_pose(world.route_W(), k);
    const SE3 T_W_C1 = T_W_C0 * SE3(Quat::Identity(), Vec3(baseline_m, 0, 0));
    cv::Mat depth;
    const cv::Mat left = render_image(world, cam, fixed(T_W_C0), 0, noiseless(), &depth);
    const cv::Mat right = render_image(world, cam, fixed(T_W_C1), 0, noiseless());
    stereo_errors(left, right, depth, cam.fx, baseline_m, errors);
  }
  ASSERT_GE(errors.size(), 200u);
  std::sort(errors.begin(), errors.end());
  const double median = errors[errors.size() / 2], p90 = errors[errors.size() * 9 / 10];
  std::cout << "stereo: " << errors.size() << " windows, |disparity - f b / z| median " << median << " px, 90% "
            << p90 << " px\n";
  EXPECT_LT(median, 0.25);
  EXPECT_LT(p90, 1.0);
}

TEST(CameraRender, NoiseGainAndDeterminism) {
  const World& world = highbay();
  const CameraIntrinsics cam = default_camera();
  const auto pose = fixed(route_camera_pose(world.route_W(), 0));
  RenderOptions o;
  o.noise_seed = 7;
  const cv::Mat a = render_image(world, cam, pose, 0, o);
  EXPECT_EQ(cv::norm(a, render_image(world, cam, pose, 0, o), cv::NORM_INF), 0) << "bit-identical";
  const cv::Mat clean = render_image(world, cam, pose, 0, noiseless());
  cv::Mat diff;
  cv::subtract(a, clean, diff, cv::noArray(), CV_32F);
  cv::Scalar mean, sd;
  cv::meanStdDev(diff, mean, sd);
  EXPECT_NEAR(sd[0], o.noise_sigma_grey, 0.2);
  EXPECT_NEAR(mean[0], 0, 0.1);
  o.noise_seed = 8;
  EXPECT_GT(cv::norm(a, render_image(world, cam, pose, 0, o), cv::NORM_L1), 0.5 * a.total()) << "seed changes noise";
  RenderOptions dim = noiseless();
  dim.exposure_gain = 0.5;
  EXPECT_NEAR(cv::mean(render_image(world, cam, pose, 0, dim))[0], 0.5 * cv::mean(clean)[0], 1.0);
}

// The rendered image as floats, for ratios and gradients.
cv::Mat render_float(const World& world, const CameraIntrinsics& cam, const std::function<SE3(TimeNs)>& pose,
                     const RenderOptions& options) {
  cv::Mat image;
  render_image(world, cam, pose, 0, options).convertTo(image, CV_32F);
  return image;
}

// Vignetting darkens the image towards its corners by the configured share of the cos^4 law.
TEST(CameraRender, VignettingDarkensTheCornersByTheCosineLaw) {
  const World& world = highbay();
  const CameraIntrinsics cam = default_camera();
  const auto pose = fixed(route_camera_pose(world.route_W(), 0));
  RenderOptions o = noiseless();
  const cv::Mat flat = render_float(world, cam, pose, o);
  o.vignetting = 0.5;
  const cv::Mat vignetted = render_float(world, cam, pose, o);
  // Pixel ratios where the flat image is bright enough for rounding not to matter.
  const auto ratio_at = [&](int r, int c) {
    const cv::Rect box(c - 4, r - 4, 9, 9);
    return cv::sum(vignetted(box))[0] / cv::sum(flat(box))[0];
  };
  const Vec3 corner_ray = unproject(cam, Eigen::Vector2d(6, 6));
  const double cos4 = std::pow(corner_ray.z(), 4);
  EXPECT_NEAR(ratio_at(240, 376), 1.0, 0.01);
  EXPECT_NEAR(ratio_at(6, 6), 0.5 + 0.5 * cos4, 0.02);
  EXPECT_LT(ratio_at(6, 6), 0.7);
}

double gradient_energy(const cv::Mat& image) {
  cv::Mat gx;
  cv::Sobel(image, gx, CV_32F, 1, 0);
  return cv::mean(gx.mul(gx))[0];
}

TEST(CameraRender, MotionBlurSmearsFastRotation) {
  const World& world = highbay();
  const CameraIntrinsics cam = default_camera();
  const SE3 T0 = route_camera_pose(world.route_W(), 0);
  // Yaw at 2 rad/s: 10 ms of exposure sweeps about 9 pixels.
  auto spinning = [T0](TimeNs t) { return T0 * SE3(so3::exp(Vec3(0, 2.0 * ns_to_s(t), 0)), Vec3::Zero()); };
  RenderOptions o = noiseless();
  o.exposure_time_s = 0.01;
  const cv::Mat sharp = render_image(world, cam, spinning, 0, o);
  o.motion_blur_samples = 9;
  cv::Mat depth;
  const cv::Mat blurred = render_image(world, cam, spinning, 0, o, &depth);
  EXPECT_LT(gradient_energy(blurred), 0.6 * gradient_energy(sharp));
  EXPECT_GT(cv::countNonZero(depth > 0), static_cast<int>(0.9 * depth.total())) << "depth at the central instant";
  // Without motion the samples agree and blur changes nothing.
  const cv::Mat still = render_image(world, cam, fixed(T0), 0, o);
  EXPECT_LE(cv::norm(still, sharp, cv::NORM_INF), 1.0);
}

// Down a tube the floor, walls and vault are seen at grazing angles. Filtered by the footprint's long axis
// alone they are blurred across too (the floor sideways, as no lens blurs it); filtered along that axis at the
// level of the short one they keep their detail across, with the same brightness on average.
TEST(CameraRender, AnisotropicFilteringKeepsGrazingSurfacesSharpAcross) {
  const World world = World::generate(Scenario::kTunnel, 1);
  const CameraIntrinsics cam = default_camera();
  const auto pose = fixed(route_camera_pose(world.route_W(), 0));
  RenderOptions o = noiseless();
  const cv::Mat isotropic = render_float(world, cam, pose, o);
  o.anisotropic_samples = 8;
  const cv::Mat anisotropic = render_float(world, cam, pose, o);
  // The floor ahead (bottom left of the image): its footprints are long in the image's vertical, so the
  // horizontal gradients show the filtering across (3.4 times the energy when written).
  const cv::Rect floor(0, 360, 400, 120);
  EXPECT_GT(gradient_energy(anisotropic(floor)), 2.0 * gradient_energy(isotropic(floor)));
  EXPECT_NEAR(cv::mean(anisotropic)[0], cv::mean(isotropic)[0], 0.5);
  o.anisotropic_samples = 0;
  EXPECT_THROW(render_image(world, cam, pose, 0, o), InputError);
}

}  // namespace
}  // namespace vilslam::sim
