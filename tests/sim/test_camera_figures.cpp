// Top-view figures: points land at their x-y pixel coloured by height; ceilings are cut; PNGs are
// written whole or not at all.
#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>

#include "common/error.h"
#include "sim/figures.h"
#include "test_util.h"

namespace vilslam::sim {
namespace {

TEST(CameraFigures, TopViewPlacesAndColoursPoints) {
  TopView view(Eigen::AlignedBox2d(Eigen::Vector2d(-10, -5), Eigen::Vector2d(10, 5)), 400);
  EXPECT_DOUBLE_EQ(view.metres_per_px(), 0.05);
  ASSERT_EQ(view.image().cols, 400);
  ASSERT_EQ(view.image().rows, 200);
  const cv::Point2d corner = view.pixel(-10, 5);
  EXPECT_NEAR(corner.x, 0, 1e-9);
  EXPECT_NEAR(corner.y, 0, 1e-9);
  // A low point at (2, 1), a high one at (-3, -2), a ceiling point above the low one.
  view.draw_points({{2.01f, 1.01f, 0.0f}, {-2.99f, -1.99f, 3.0f}, {2.01f, 1.01f, 9.0f}}, 0.0, 3.0, 5.0);
  const cv::Vec3b low = view.image().at<cv::Vec3b>(79, 240);   // row (5 - 1.01) / 0.05, col (2.01 + 10) / 0.05
  const cv::Vec3b high = view.image().at<cv::Vec3b>(139, 140);
  EXPECT_NE(low, cv::Vec3b(255, 255, 255));
  EXPECT_GT(low[0], low[2]) << "low points are blue, the ceiling point above is cut";
  EXPECT_GT(high[2], high[0]) << "high points are red";
  EXPECT_EQ(view.image().at<cv::Vec3b>(100, 100), cv::Vec3b(255, 255, 255)) << "no point there";
  int coloured = 0;
  for (int r = 0; r < view.image().rows; ++r)
    for (int c = 0; c < view.image().cols; ++c) coloured += view.image().at<cv::Vec3b>(r, c) != cv::Vec3b(255, 255, 255);
  EXPECT_EQ(coloured, 2);
}

TEST(CameraFigures, PathIsDrawnThroughItsPoints) {
  TopView view(Eigen::AlignedBox2d(Eigen::Vector2d(0, 0), Eigen::Vector2d(10, 10)), 200);
  view.draw_path({Vec3(1, 1, 0), Vec3(9, 1, 0), Vec3(9, 9, 0)}, cv::Scalar(0, 0, 0), 2);
  EXPECT_LT(view.image().at<cv::Vec3b>(180, 100)[0], 128) << "on the segment y = 1";
  EXPECT_LT(view.image().at<cv::Vec3b>(100, 180)[0], 128) << "on the segment x = 9";
  EXPECT_EQ(view.image().at<cv::Vec3b>(60, 60), cv::Vec3b(255, 255, 255));
}

TEST(CameraFigures, WritePngIsAtomic) {
  const auto dir = test::temp_dir();
  const cv::Mat img(20, 30, CV_8UC3, cv::Scalar(10, 20, 30));
  write_png((dir / "a.png").string(), img);
  const cv::Mat back = cv::imread((dir / "a.png").string(), cv::IMREAD_COLOR);
  ASSERT_EQ(back.size(), img.size());
  EXPECT_EQ(cv::norm(back, img, cv::NORM_INF), 0);
  EXPECT_THROW(write_png((dir / "missing" / "b.png").string(), img), InputError);
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir), std::filesystem::directory_iterator()), 1)
      << "no temporary file is left behind";
}

}  // namespace
}  // namespace vilslam::sim
