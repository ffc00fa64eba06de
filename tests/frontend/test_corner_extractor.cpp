#include <gtest/gtest.h>

#include <random>

#include "frontend/corner_extractor.h"
#include "synthetic_stereo.h"

namespace vilslam {
namespace {

std::vector<cv::Point2f> random_points(int count, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0, 752), v(0, 480);
  std::vector<cv::Point2f> points;
  for (int i = 0; i < count; ++i) points.emplace_back(u(rng), v(rng));
  return points;
}

bool near_any(const cv::Point2f& p, const std::vector<cv::Point2f>& others, double distance) {
  for (const cv::Point2f& q : others) {
    if (cv::norm(p - q) < distance) return true;
  }
  return false;
}

TEST(CornerExtractor, EliminationMatchesBruteForce) {
  const std::vector<cv::Point2f> corners = random_points(2000, 1), existing = random_points(150, 2);
  const double distance = 15;
  std::vector<cv::Point2f> expected;
  for (const cv::Point2f& c : corners) {
    if (!near_any(c, existing, distance)) expected.push_back(c);
  }
  const std::vector<cv::Point2f> kept = eliminate_near_features(corners, existing, distance);
  ASSERT_EQ(kept.size(), expected.size());
  for (std::size_t i = 0; i < kept.size(); ++i) EXPECT_EQ(kept[i], expected[i]);
  EXPECT_LT(kept.size(), corners.size());
  EXPECT_GT(kept.size(), corners.size() / 4);
}

TEST(CornerExtractor, EliminationKeepsExactlyTheFarOnes) {
  const std::vector<cv::Point2f> existing = {{100, 100}, {-3, -3}};
  const std::vector<cv::Point2f> corners = {{109.9f, 100}, {110.1f, 100}, {100, 90.5f}, {3, 3}, {5, 5}, {400, 300}};
  const std::vector<cv::Point2f> kept = eliminate_near_features(corners, existing, 10);
  const std::vector<cv::Point2f> expected = {{110.1f, 100}, {5, 5}, {400, 300}};
  EXPECT_EQ(kept, expected);
  EXPECT_EQ(eliminate_near_features(corners, {}, 10), corners);
}

TEST(CornerExtractor, DetectsSpreadCornersAndDescribesInOrder) {
  const cv::Mat image = test::random_texture(752, 480, 7);
  FrontendConfig config;
  config.corner_subpix_half_window_px = 0;  // the spacing holds before the sub-pixel refinement moves corners
  const std::vector<cv::Point2f> corners = detect_corners(image, config);
  ASSERT_GT(corners.size(), 200u);
  ASSERT_LE(corners.size(), static_cast<std::size_t>(config.max_corners));
  for (std::size_t i = 0; i < corners.size(); ++i) {
    for (std::size_t j = i + 1; j < corners.size(); ++j) {
      ASSERT_GE(cv::norm(corners[i] - corners[j]), config.corner_min_distance_px - 1e-3);
    }
  }
  // Corners too close to the border for the descriptor patch are dropped, the others keep their order.
  const int border = config.orb_patch_size / 2 + 1;
  const cv::Rect inner(border, border, image.cols - 2 * border, image.rows - 2 * border);
  std::vector<cv::Point2f> expected;
  for (const cv::Point2f& c : corners) {
    if (inner.contains(c)) expected.push_back(c);
  }
  ASSERT_LT(expected.size(), corners.size());
  std::vector<cv::Point2f> described = corners;
  described.push_back({2, 2});
  const cv::Mat descriptors = describe_corners(image, &described, config);
  EXPECT_EQ(described, expected);
  EXPECT_EQ(descriptors.rows, static_cast<int>(expected.size()));
  EXPECT_EQ(descriptors.cols, 32);
  // The same corner described on its own gets the same descriptor (descriptors are per corner).
  std::vector<cv::Point2f> single = {expected[5]};
  const cv::Mat one = describe_corners(image, &single, config);
  EXPECT_EQ(cv::norm(one.row(0), descriptors.row(5), cv::NORM_HAMMING), 0);
  EXPECT_GT(cv::norm(one.row(0), descriptors.row(6), cv::NORM_HAMMING), 0);
}

}  // namespace
}  // namespace vilslam
