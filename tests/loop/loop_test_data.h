#pragma once
// Test data for the loop tests: file bytes, and real images: EuRoC V1_01 micro left frames, cut into tiles (distinct
// places with real texture, since the MAV hardly moves in these 4.7 s), and a noise image unrelated to them.
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <random>
#include <string>
#include <vector>

namespace vilslam::test {

// The left images of an EuRoC folder (mav0/cam0/data/*.png) in time order.
inline std::vector<std::string> euroc_left_paths(const std::string& sequence_dir) {
  std::vector<std::string> paths;
  for (const auto& e : std::filesystem::directory_iterator(sequence_dir + "/mav0/cam0/data")) {
    if (e.path().extension() == ".png") paths.push_back(e.path().string());
  }
  std::sort(paths.begin(), paths.end());
  return paths;
}

inline cv::Mat read_grey(const std::string& path) { return cv::imread(path, cv::IMREAD_GRAYSCALE); }

// rows x cols tiles of the image, row by row (each a copy).
inline std::vector<cv::Mat> tiles(const cv::Mat& image, int rows, int cols) {
  std::vector<cv::Mat> out;
  const int h = image.rows / rows, w = image.cols / cols;
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < cols; ++c) out.push_back(image(cv::Rect(c * w, r * h, w, h)).clone());
  }
  return out;
}

inline cv::Mat noise_image(int rows, int cols, unsigned seed) {
  cv::Mat noise(rows, cols, CV_8U);
  std::mt19937 rng(seed);
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < cols; ++c) noise.at<std::uint8_t>(r, c) = static_cast<std::uint8_t>(rng() & 0xff);
  }
  return noise;
}

}  // namespace vilslam::test
