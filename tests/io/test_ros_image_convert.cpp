// sensor_msgs/Image encodings to 8-bit grey (io/ros_convert.h): colour with alpha, Bayer mosaics in ROS's
// four patterns, 16-bit samples in either byte order with their significant bits, and refused messages.
#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "io/ros_convert.h"
#include "io/ros_wire.h"

namespace vilslam {
namespace {

RosImage message(const cv::Mat& pixels, const std::string& encoding, int padding_bytes = 0) {
  RosImage m;
  m.encoding = encoding;
  m.height = static_cast<std::uint32_t>(pixels.rows);
  m.width = static_cast<std::uint32_t>(pixels.cols);
  const std::size_t row_bytes = pixels.cols * pixels.elemSize();
  m.step = static_cast<std::uint32_t>(row_bytes + padding_bytes);
  m.data.assign(std::size_t{m.step} * m.height, 0xAB);  // padding that must not be read
  for (int r = 0; r < pixels.rows; ++r) std::memcpy(m.data.data() + std::size_t{m.step} * r, pixels.ptr(r), row_bytes);
  return m;
}

// A saturated, smoothly varying colour image (BGR): red, green and blue differ everywhere, so a demosaic that
// mistakes one colour site for another changes the grey (0.299 R + 0.587 G + 0.114 B).
cv::Mat colour_ramp() {
  cv::Mat bgr(48, 64, CV_8UC3);
  for (int r = 0; r < bgr.rows; ++r) {
    for (int c = 0; c < bgr.cols; ++c) bgr.at<cv::Vec3b>(r, c) = cv::Vec3b(static_cast<uchar>(20 + 2 * r), 60, static_cast<uchar>(230 - 2 * c));
  }
  return bgr;
}

// The mosaic a sensor with ROS's pattern (first 2x2 block, row by row, e.g. "rggb") records of a BGR image.
cv::Mat mosaic(const cv::Mat& bgr, const std::string& pattern) {
  cv::Mat raw(bgr.size(), CV_8UC1);
  for (int r = 0; r < bgr.rows; ++r) {
    for (int c = 0; c < bgr.cols; ++c) {
      const char site = pattern[2 * (r % 2) + (c % 2)];
      const int channel = site == 'b' ? 0 : site == 'g' ? 1 : 2;
      raw.at<uchar>(r, c) = bgr.at<cv::Vec3b>(r, c)[channel];
    }
  }
  return raw;
}

// Mean absolute grey difference away from the border (demosaicing interpolates there).
double interior_error(const cv::Mat& a, const cv::Mat& b) {
  const cv::Rect inner(4, 4, a.cols - 8, a.rows - 8);
  cv::Mat diff;
  cv::absdiff(a(inner), b(inner), diff);
  return cv::mean(diff)[0];
}

TEST(RosImageConvert, BayerPatternsDemosaicToTheSceneGrey) {
  const cv::Mat bgr = colour_ramp();
  cv::Mat truth;
  cv::cvtColor(bgr, truth, cv::COLOR_BGR2GRAY);
  const std::string patterns[] = {"rggb", "bggr", "gbrg", "grbg"};
  for (const std::string& recorded : patterns) {
    SCOPED_TRACE(recorded);
    const cv::Mat raw = mosaic(bgr, recorded);
    for (const std::string& named : patterns) {
      const double error = interior_error(grey_from_ros_image(message(raw, "bayer_" + named + "8", 3)), truth);
      // The right pattern gives the scene's grey within a grey level; any other is off by tens.
      if (named == recorded) {
        EXPECT_LT(error, 1.0) << named;
      } else {
        EXPECT_GT(error, 10.0) << named;
      }
    }
    // 16-bit mosaic of the same scene at 12 bits (v << 4 | v >> 4 maps back to v exactly).
    cv::Mat raw16(raw.size(), CV_16UC1);
    for (int i = 0; i < raw.rows * raw.cols; ++i) raw16.at<std::uint16_t>(i) = (raw.at<uchar>(i) << 4) | (raw.at<uchar>(i) >> 4);
    EXPECT_LT(interior_error(grey_from_ros_image(message(raw16, "bayer_" + recorded + "16"), 12), truth), 1.0);
  }
}

TEST(RosImageConvert, ColourWithAlphaKeepsGreyPixels) {
  cv::Mat grey(5, 7, CV_8UC1);
  for (int i = 0; i < grey.rows * grey.cols; ++i) grey.at<uchar>(i) = static_cast<uchar>(7 * i);
  cv::Mat rgba;
  cv::cvtColor(grey, rgba, cv::COLOR_GRAY2RGBA);
  for (const char* encoding : {"rgba8", "bgra8"}) {
    const cv::Mat out = grey_from_ros_image(message(rgba, encoding, 2));
    EXPECT_EQ(cv::norm(out, grey, cv::NORM_INF), 0.0) << encoding;
  }
  EXPECT_EQ(cv::norm(grey_from_ros_image(message(grey, "8UC1", 1)), grey, cv::NORM_INF), 0.0);
}

TEST(RosImageConvert, SixteenBitSamplesScaleFromTheirSignificantBits) {
  // Every 8-bit value as a right-aligned 12-bit sample, little- and big-endian.
  cv::Mat grey(1, 256, CV_8UC1), twelve(1, 256, CV_16UC1);
  for (int v = 0; v < 256; ++v) {
    grey.at<uchar>(v) = static_cast<uchar>(v);
    twelve.at<std::uint16_t>(v) = static_cast<std::uint16_t>((v << 4) | (v >> 4));
  }
  RosImage little = message(twelve, "mono16");
  EXPECT_EQ(ros_image_significant_bits(little), 12);
  EXPECT_EQ(cv::norm(grey_from_ros_image(little, 12), grey, cv::NORM_INF), 0.0);
  RosImage big = little;
  big.is_bigendian = 1;
  for (std::size_t i = 0; i + 1 < big.data.size(); i += 2) std::swap(big.data[i], big.data[i + 1]);
  EXPECT_EQ(ros_image_significant_bits(big), 12);
  EXPECT_EQ(cv::norm(grey_from_ros_image(big, 12), grey, cv::NORM_INF), 0.0);
  // Read as full 16-bit data the same samples are 16 times darker.
  EXPECT_EQ(grey_from_ros_image(little, 16).at<uchar>(255), 16);
  // A sample above the full scale clips to white.
  EXPECT_EQ(grey_from_ros_image(message(cv::Mat(1, 1, CV_16UC1, cv::Scalar(5000)), "16UC1"), 12).at<uchar>(0), 255);

  // Significant bits: the smallest b >= 8 with every sample below 2^b; 8-bit encodings have none.
  const auto bits_of = [](int max_sample) {
    return ros_image_significant_bits(message(cv::Mat(2, 3, CV_16UC1, cv::Scalar(max_sample)), "mono16"));
  };
  EXPECT_EQ(bits_of(0), 8);
  EXPECT_EQ(bits_of(255), 8);
  EXPECT_EQ(bits_of(256), 9);
  EXPECT_EQ(bits_of(4095), 12);
  EXPECT_EQ(bits_of(4096), 13);
  EXPECT_EQ(bits_of(65535), 16);
  EXPECT_EQ(ros_image_significant_bits(message(grey, "mono8")), 0);
}

TEST(RosImageConvert, RefusesWhatItCannotRead) {
  const auto refused = [](const RosImage& m, const std::string& says) {
    try {
      grey_from_ros_image(m);
      ADD_FAILURE() << "accepted: " << says;
    } catch (const WireError& e) {
      EXPECT_NE(std::string(e.what()).find(says), std::string::npos) << e.what();
    }
  };
  const cv::Mat grey(4, 6, CV_8UC1, cv::Scalar(9));
  refused(message(grey, "yuv422"), "'yuv422' is not supported (mono8, 8UC1, mono16");
  RosImage short_step = message(grey, "mono16");  // 6 bytes a row for 6 16-bit samples
  refused(short_step, "step 6 < width x bytes per pixel 12");
  RosImage odd = message(cv::Mat(4, 3, CV_8UC1, cv::Scalar(1)), "mono16", 7);
  odd.step = 7;
  odd.data.resize(28);
  refused(odd, "odd step 7");
  RosImage cut = message(grey, "mono8");
  cut.data.pop_back();
  refused(cut, "image data has 23 bytes");
  refused(message(cv::Mat(1, 6, CV_8UC1, cv::Scalar(1)), "bayer_rggb8"), "smaller than 2x2");
  EXPECT_THROW(grey_from_ros_image(message(grey, "mono8"), 7), std::invalid_argument);
}

}  // namespace
}  // namespace vilslam
