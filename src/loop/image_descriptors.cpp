#include "loop/image_descriptors.h"

#include <opencv2/imgproc.hpp>
#include <stdexcept>
#include <utility>

#include "frontend/corner_extractor.h"

namespace vilslam {

cv::Mat describe_image(const cv::Mat& image, const FrontendConfig& config, std::vector<cv::Point2f>* corners_out) {
  if (image.depth() != CV_8U || (image.channels() != 1 && image.channels() != 3)) {
    throw std::invalid_argument("describe_image needs an 8-bit grey or BGR image");
  }
  cv::Mat grey = image;
  if (image.channels() == 3) cv::cvtColor(image, grey, cv::COLOR_BGR2GRAY);
  std::vector<cv::Point2f> corners = detect_corners(grey, config);
  const cv::Mat descriptors = corners.empty() ? cv::Mat(0, 32, CV_8U) : describe_corners(grey, &corners, config);
  if (corners_out) *corners_out = std::move(corners);
  return descriptors;
}

}  // namespace vilslam
