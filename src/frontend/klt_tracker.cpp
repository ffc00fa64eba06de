#include "frontend/klt_tracker.h"

#include <opencv2/video/tracking.hpp>

#include <algorithm>

namespace vilslam {
namespace {

cv::TermCriteria klt_criteria(const FrontendConfig& config) {
  return {cv::TermCriteria::COUNT | cv::TermCriteria::EPS, config.klt_max_iterations, config.klt_epsilon};
}

bool inside(const cv::Point2f& p, const cv::Size& size) {
  return p.x >= 0 && p.y >= 0 && p.x <= size.width - 1 && p.y <= size.height - 1;
}

constexpr int kRefineMaxLevel = 1;

// Forward LK from prev to cur (from *cur_px when flags has cv::OPTFLOW_USE_INITIAL_FLOW), then backward
// for the points the forward pass kept inside the image: the others are lost whatever the backward pass
// gives, and LK tracks each point on its own.
void track_forward_backward(const ImagePyramid& prev, const ImagePyramid& cur,
                            const std::vector<cv::Point2f>& prev_px, const FrontendConfig& config, int max_level,
                            int flags, std::vector<cv::Point2f>* cur_px, std::vector<bool>* tracked) {
  tracked->assign(prev_px.size(), false);
  if (prev_px.empty()) return;
  const cv::Size window(config.klt_window_px, config.klt_window_px);
  std::vector<uchar> forward_ok, backward_ok;
  std::vector<float> errors;
  cv::calcOpticalFlowPyrLK(prev, cur, prev_px, *cur_px, forward_ok, errors, window, max_level, klt_criteria(config),
                           flags);
  if (config.klt_final_window_px > 0) {
    // The finest level again with the smaller window, from the pyramidal result: the coarse levels keep the large
    // window's reach, while the final estimate averages the flow over less of a surface whose flow varies across
    // the window (docs/frontend.md, "The KLT window ... the tunnel's long legs").
    const cv::Size final_window(config.klt_final_window_px, config.klt_final_window_px);
    std::vector<uchar> final_ok;
    cv::calcOpticalFlowPyrLK(prev, cur, prev_px, *cur_px, final_ok, errors, final_window, 0, klt_criteria(config),
                             cv::OPTFLOW_USE_INITIAL_FLOW);
    for (std::size_t i = 0; i < forward_ok.size(); ++i) forward_ok[i] = forward_ok[i] && final_ok[i];
  }
  const cv::Size size = cur.front().size();
  std::vector<std::size_t> forward_kept;
  std::vector<cv::Point2f> kept_cur_px, back_px;
  for (std::size_t i = 0; i < prev_px.size(); ++i) {
    if (!forward_ok[i] || !inside((*cur_px)[i], size)) continue;
    forward_kept.push_back(i);
    kept_cur_px.push_back((*cur_px)[i]);
    back_px.push_back(prev_px[i]);
  }
  if (forward_kept.empty()) return;
  cv::calcOpticalFlowPyrLK(cur, prev, kept_cur_px, back_px, backward_ok, errors, window, max_level,
                           klt_criteria(config), cv::OPTFLOW_USE_INITIAL_FLOW);
  const double max_fb_sq = config.klt_max_forward_backward_px * config.klt_max_forward_backward_px;
  for (std::size_t k = 0; k < forward_kept.size(); ++k) {
    const std::size_t i = forward_kept[k];
    const cv::Point2f d = back_px[k] - prev_px[i];
    (*tracked)[i] = backward_ok[k] && d.dot(d) <= max_fb_sq;
  }
}

}  // namespace

ImagePyramid build_klt_pyramid(const cv::Mat& image, const FrontendConfig& config) {
  ImagePyramid pyramid;
  const cv::Size window(config.klt_window_px, config.klt_window_px);
  cv::buildOpticalFlowPyramid(image, pyramid, window, config.klt_pyramid_levels, true);
  return pyramid;
}

void track_klt(const ImagePyramid& prev, const ImagePyramid& cur, const std::vector<cv::Point2f>& prev_px,
               const FrontendConfig& config, std::vector<cv::Point2f>* cur_px, std::vector<bool>* tracked) {
  cur_px->clear();
  track_forward_backward(prev, cur, prev_px, config, config.klt_pyramid_levels, 0, cur_px, tracked);
}

void refine_klt(const ImagePyramid& prev, const ImagePyramid& cur, const std::vector<cv::Point2f>& prev_px,
                const FrontendConfig& config, std::vector<cv::Point2f>* cur_px, std::vector<bool>* tracked) {
  const int max_level = std::min(config.klt_pyramid_levels, kRefineMaxLevel);
  track_forward_backward(prev, cur, prev_px, config, max_level, cv::OPTFLOW_USE_INITIAL_FLOW, cur_px, tracked);
}

}  // namespace vilslam
