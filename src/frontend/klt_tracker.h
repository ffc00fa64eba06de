#pragma once
// Pyramidal Lucas-Kanade tracking with a forward-backward consistency check.
#include <opencv2/core.hpp>
#include <vector>

#include "frontend/frontend_config.h"

namespace vilslam {

// Image pyramid with gradients (cv::buildOpticalFlowPyramid), built once per image and reused by the
// forward pass (as the next image) and the backward pass and the next pair (as the previous image).
using ImagePyramid = std::vector<cv::Mat>;

ImagePyramid build_klt_pyramid(const cv::Mat& image, const FrontendConfig& config);

// Tracks prev_px from prev into cur. tracked[i] is true when LK converged both ways, the backward track
// lands within klt_max_forward_backward_px of prev_px[i] and cur_px[i] lies inside the image.
void track_klt(const ImagePyramid& prev, const ImagePyramid& cur, const std::vector<cv::Point2f>& prev_px,
               const FrontendConfig& config, std::vector<cv::Point2f>* cur_px, std::vector<bool>* tracked);

// Like track_klt, but starts from the positions in *cur_px (same size as prev_px), which must already be
// within a few pixels: only the two finest pyramid levels are used.
void refine_klt(const ImagePyramid& prev, const ImagePyramid& cur, const std::vector<cv::Point2f>& prev_px,
                const FrontendConfig& config, std::vector<cv::Point2f>* cur_px, std::vector<bool>* tracked);

}  // namespace vilslam
