#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>

#include "frontend/corner_extractor.h"
#include "frontend/klt_tracker.h"
#include "synthetic_stereo.h"

namespace vilslam {
namespace {

cv::Mat shifted(const cv::Mat& image, double dx, double dy) {
  const cv::Mat A = (cv::Mat_<double>(2, 3) << 1, 0, dx, 0, 1, dy);
  cv::Mat out;
  cv::warpAffine(image, out, A, image.size(), cv::INTER_LINEAR, cv::BORDER_REFLECT);
  return out;
}

TEST(KltTracker, RecoversKnownSubpixelShift) {
  const FrontendConfig config;
  const cv::Mat prev = test::random_texture(752, 480, 11);
  const double dx = 7.3, dy = -4.6;
  const cv::Mat cur = shifted(prev, dx, dy);
  const std::vector<cv::Point2f> prev_px = detect_corners(prev, config);
  ASSERT_GT(prev_px.size(), 100u);
  std::vector<cv::Point2f> cur_px;
  std::vector<bool> tracked;
  track_klt(build_klt_pyramid(prev, config), build_klt_pyramid(cur, config), prev_px, config, &cur_px, &tracked);
  std::vector<double> errors_px;
  for (std::size_t i = 0; i < prev_px.size(); ++i) {
    const bool interior = prev_px[i].x > 30 && prev_px[i].y > 30 && prev_px[i].x < 722 && prev_px[i].y < 450;
    if (!interior) continue;
    EXPECT_TRUE(tracked[i]) << i;
    if (!tracked[i]) continue;
    // Bilinear resampling of the shifted image bends the truth a little: 0.2 px at worst, 0.05 px typically.
    const double error = std::hypot(cur_px[i].x - prev_px[i].x - dx, cur_px[i].y - prev_px[i].y - dy);
    EXPECT_LT(error, 0.2);
    errors_px.push_back(error);
  }
  ASSERT_GT(errors_px.size(), 100u);
  std::nth_element(errors_px.begin(), errors_px.begin() + errors_px.size() / 2, errors_px.end());
  EXPECT_LT(errors_px[errors_px.size() / 2], 0.05);
}

TEST(KltTracker, ForwardBackwardCheckDropsVanishedContent) {
  const FrontendConfig config;
  const cv::Mat prev = test::random_texture(752, 480, 12);
  cv::Mat cur = shifted(prev, 2.0, 1.0);
  // The right half of the new image shows different content: tracks there must not survive.
  test::random_texture(376, 480, 99).copyTo(cur(cv::Rect(376, 0, 376, 480)));
  const std::vector<cv::Point2f> prev_px = detect_corners(prev, config);
  std::vector<cv::Point2f> cur_px;
  std::vector<bool> tracked;
  track_klt(build_klt_pyramid(prev, config), build_klt_pyramid(cur, config), prev_px, config, &cur_px, &tracked);
  int left_total = 0, left_tracked = 0, right_total = 0, right_tracked = 0;
  for (std::size_t i = 0; i < prev_px.size(); ++i) {
    if (prev_px[i].x < 330 && prev_px[i].x > 30 && prev_px[i].y > 30 && prev_px[i].y < 450) {
      ++left_total;
      left_tracked += tracked[i];
    } else if (prev_px[i].x > 420) {
      ++right_total;
      right_tracked += tracked[i];
    }
  }
  ASSERT_GT(left_total, 50);
  ASSERT_GT(right_total, 50);
  EXPECT_GT(left_tracked, 0.95 * left_total);
  EXPECT_LT(right_tracked, 0.1 * right_total);
}

}  // namespace
}  // namespace vilslam
