#include "frontend/corner_extractor.h"

#include <opencv2/features2d.hpp>
#include <opencv2/imgproc.hpp>

#include <cmath>
#include <unordered_map>

namespace vilslam {
namespace {

// Existing features binned in square cells of the elimination distance: a corner only needs the 3x3
// cells around its own.
class FeatureGrid {
 public:
  FeatureGrid(const std::vector<cv::Point2f>& points, double cell_px) : cell_px_(cell_px) {
    for (const cv::Point2f& p : points) cells_[key(cell_of(p.x), cell_of(p.y))].push_back(p);
  }

  bool any_within(const cv::Point2f& p, double distance_px) const {
    const long cx = cell_of(p.x), cy = cell_of(p.y);
    const double limit_sq = distance_px * distance_px;
    for (long dy = -1; dy <= 1; ++dy) {
      for (long dx = -1; dx <= 1; ++dx) {
        const auto it = cells_.find(key(cx + dx, cy + dy));
        if (it == cells_.end()) continue;
        for (const cv::Point2f& q : it->second) {
          const cv::Point2f d = p - q;
          if (d.dot(d) < limit_sq) return true;
        }
      }
    }
    return false;
  }

 private:
  long cell_of(float v) const { return static_cast<long>(std::floor(v / cell_px_)); }
  // Both cell indices' 32-bit patterns in one key (unsigned: shifting a negative signed value is undefined).
  static unsigned long long key(long cx, long cy) {
    return (static_cast<unsigned long long>(cx) << 32) ^ (static_cast<unsigned long long>(cy) & 0xffffffffULL);
  }

  double cell_px_;
  std::unordered_map<unsigned long long, std::vector<cv::Point2f>> cells_;
};

}  // namespace

std::vector<cv::Point2f> detect_corners(const cv::Mat& image, const FrontendConfig& config) {
  std::vector<cv::Point2f> corners;
  cv::goodFeaturesToTrack(image, corners, config.max_corners, config.corner_quality, config.corner_min_distance_px,
                          cv::noArray(), config.corner_block_size);
  if (!corners.empty() && config.corner_subpix_half_window_px > 0) {
    const cv::Size half_window(config.corner_subpix_half_window_px, config.corner_subpix_half_window_px);
    cv::cornerSubPix(image, corners, half_window, cv::Size(-1, -1),
                     cv::TermCriteria(cv::TermCriteria::COUNT | cv::TermCriteria::EPS, 20, 0.01));
  }
  return corners;
}

std::vector<cv::Point2f> eliminate_near_features(const std::vector<cv::Point2f>& corners,
                                                 const std::vector<cv::Point2f>& existing, double min_distance_px) {
  if (existing.empty() || min_distance_px <= 0) return corners;
  const FeatureGrid grid(existing, min_distance_px);
  std::vector<cv::Point2f> kept;
  kept.reserve(corners.size());
  for (const cv::Point2f& c : corners) {
    if (!grid.any_within(c, min_distance_px)) kept.push_back(c);
  }
  return kept;
}

cv::Mat describe_corners(const cv::Mat& image, std::vector<cv::Point2f>* corners, const FrontendConfig& config) {
  std::vector<cv::KeyPoint> keypoints;
  keypoints.reserve(corners->size());
  for (std::size_t i = 0; i < corners->size(); ++i) {
    // angle 0: upright descriptors, stereo pairs are not rotated against each other.
    keypoints.emplace_back((*corners)[i], static_cast<float>(config.orb_patch_size), 0.f, 0.f, 0, static_cast<int>(i));
  }
  const int edge_px = config.orb_patch_size / 2 + 1;
  const cv::Ptr<cv::ORB> orb = cv::ORB::create(static_cast<int>(keypoints.size()) + 1, 1.2f, 1, edge_px, 0, 2,
                                               cv::ORB::HARRIS_SCORE, config.orb_patch_size);
  cv::Mat descriptors;
  orb->compute(image, keypoints, descriptors);
  std::vector<cv::Point2f> kept;
  kept.reserve(keypoints.size());
  for (const cv::KeyPoint& kp : keypoints) kept.push_back((*corners)[kp.class_id]);
  *corners = std::move(kept);
  return descriptors;
}

}  // namespace vilslam
