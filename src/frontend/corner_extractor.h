#pragma once
// New features: Shi-Tomasi corners, elimination near existing features, ORB descriptors.
#include <opencv2/core.hpp>
#include <vector>

#include "frontend/frontend_config.h"

namespace vilslam {

// Shi-Tomasi corners (cv::goodFeaturesToTrack), strongest first, refined to sub-pixel (cv::cornerSubPix).
std::vector<cv::Point2f> detect_corners(const cv::Mat& image, const FrontendConfig& config);

// The corners farther than min_distance_px from every existing feature, in their input order.
std::vector<cv::Point2f> eliminate_near_features(const std::vector<cv::Point2f>& corners,
                                                 const std::vector<cv::Point2f>& existing, double min_distance_px);

// Upright ORB descriptors (one 32-byte row per kept corner). Corners too close to the border for the
// descriptor patch are dropped from `corners`, which keeps its order.
cv::Mat describe_corners(const cv::Mat& image, std::vector<cv::Point2f>* corners, const FrontendConfig& config);

}  // namespace vilslam
