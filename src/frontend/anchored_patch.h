#pragma once
// Drift-free refinement of a KLT track against the patch where the track began (Shi and Tomasi, "Good
// features to track", CVPR 1994: the first appearance under an affine warp). Frame-to-frame KLT re-learns its
// template every frame, so the small bias of each step adds up along a track: in forward motion the texture
// around a feature expands unevenly, the translation-only window is pulled outward and the scene seems to
// approach faster (docs/frontend.md, "Anchored tracks"). Matching the first patch under an affine warp with a
// gain and offset ties the track to the point it started on instead.
#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <vector>

namespace vilslam {

// The first appearance of a feature and the warp that maps it into the latest image.
struct PatchAnchor {
  std::vector<float> patch;                     // (2 h + 1)^2 samples of the first image around the feature
  int half_px = 0;                              // h
  Eigen::Matrix2d A = Eigen::Matrix2d::Identity();  // offset in the first image -> offset in the latest one
  double gain = 1.0, bias = 0.0;                // latest intensity = gain * first intensity + bias
  // The Gauss-Newton normal matrix of the last refinement; has_normal is false before the first.
  Eigen::Matrix<double, 8, 8> normal = Eigen::Matrix<double, 8, 8>::Zero();
  bool has_normal = false;
};

struct AnchorRefinementConfig {
  int max_iterations = 30;         // 10 left 8 % of the steps unconverged on the realistic tunnel, 30 1 %
  double max_correction_px = 0.3;  // farther from the KLT position than this: the track is given up
  // Normalized correlation of the warped patch with the first one. The tunnel's faint concrete under sensor
  // noise correlates at 0.5-0.8; 0.8 ended 15 % of the steps there and starved the VIO of tracks.
  double min_correlation = 0.5;
  double min_scale = 0.5, max_scale = 3.0;  // sqrt(det A): the patch's zoom since the first image
};

// Samples the patch of `image` (8-bit grey) around px; false when it does not fit inside the image.
bool make_anchor(const cv::Mat& image, const Eigen::Vector2d& px, int half_px, PatchAnchor* anchor);

// Gauss-Newton on the warp (position, A, gain, bias) from *px (the KLT position) and anchor->A: every sample
// of the first patch at offset x against image(px + A x). derivatives: the image's Scharr derivatives as
// cv::buildOpticalFlowPyramid keeps them beside each level (CV_16SC2; ImagePyramid element 1). On success *px
// and the anchor's warp are updated; false (both unchanged) when it leaves the image, does not converge, moves
// more than max_correction_px, correlates less than min_correlation or zooms beyond the bounds.
bool refine_to_anchor(const cv::Mat& image, const cv::Mat& derivatives, const AnchorRefinementConfig& config,
                      Eigen::Vector2d* px, PatchAnchor* anchor);

}  // namespace vilslam
