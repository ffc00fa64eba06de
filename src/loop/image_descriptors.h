#pragma once
// ORB descriptors of a whole image with the frontend's own extraction (Shi-Tomasi corners, upright ORB),
// so that the vocabulary is trained on, and queried with, the descriptors the frontend computes.
#include <opencv2/core.hpp>
#include <vector>

#include "frontend/frontend_config.h"

namespace vilslam {

// N x 32 CV_8U descriptors of an 8-bit grey (or BGR, converted) image; empty when it has no corners.
// corners (optional) receives the pixel of each descriptor row.
cv::Mat describe_image(const cv::Mat& image, const FrontendConfig& config = FrontendConfig(),
                       std::vector<cv::Point2f>* corners = nullptr);

}  // namespace vilslam
