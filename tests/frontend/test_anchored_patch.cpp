#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>

#include "frontend/anchored_patch.h"
#include "frontend/corner_extractor.h"
#include "frontend/klt_tracker.h"
#include "synthetic_stereo.h"
#include "test_util.h"

namespace vilslam {
namespace {

// The image zoomed by `scale` about `centre`, its intensities mapped by gain and bias.
cv::Mat zoomed(const cv::Mat& image, double scale, const cv::Point2d& centre, double gain, double bias) {
  const cv::Mat A = (cv::Mat_<double>(2, 3) << scale, 0, centre.x * (1 - scale), 0, scale, centre.y * (1 - scale));
  cv::Mat out;
  cv::warpAffine(image, out, A, image.size(), cv::INTER_LINEAR, cv::BORDER_REFLECT);
  out.convertTo(out, CV_8U, gain, bias);
  return out;
}

struct ZoomTracks {
  std::size_t started = 0;
  std::vector<double> errors_px;       // of the surviving tracks at the last frame, sorted
  std::vector<PatchAnchor> anchors;    // of the surviving tracks
};

// A forward-moving camera's view: ten frames, each 2 % closer than the last, the last five 15 % darker and
// offset. Tracked frame to frame by KLT, each step refined against the first patch when `anchored`.
ZoomTracks track_zoom(bool anchored) {
  const FrontendConfig config;
  const cv::Mat first = test::random_texture(752, 480, 5);
  const cv::Point2d centre(376, 240);
  std::vector<cv::Point2f> start, cur;
  std::vector<PatchAnchor> anchors;
  for (const cv::Point2f& p : detect_corners(first, config)) {
    // Inside the image over the whole zoom (1.02^10 = 1.22).
    if (std::abs(p.x - centre.x) > 250 || std::abs(p.y - centre.y) > 150) continue;
    PatchAnchor anchor;
    if (!make_anchor(first, Eigen::Vector2d(p.x, p.y), 7, &anchor)) continue;
    start.push_back(p);
    anchors.push_back(anchor);
  }
  cur = start;
  // The brightness step throws KLT further than the default 0.3 px from where the anchor is.
  AnchorRefinementConfig refinement;
  refinement.max_correction_px = 1.0;
  std::vector<bool> alive(start.size(), true);
  cv::Mat prev = first;
  double scale = 1.0;
  for (int frame = 1; frame <= 10; ++frame) {
    scale *= 1.02;
    const cv::Mat image = zoomed(first, scale, centre, frame > 5 ? 0.85 : 1.0, frame > 5 ? 12.0 : 0.0);
    std::vector<cv::Point2f> next;
    std::vector<bool> tracked;
    const ImagePyramid pyramid = build_klt_pyramid(image, config);
    track_klt(build_klt_pyramid(prev, config), pyramid, cur, config, &next, &tracked);
    for (std::size_t i = 0; i < cur.size(); ++i) {
      alive[i] = alive[i] && tracked[i];
      if (!alive[i]) continue;
      Eigen::Vector2d p(next[i].x, next[i].y);
      if (anchored) alive[i] = refine_to_anchor(image, pyramid[1], refinement, &p, &anchors[i]);
      cur[i] = cv::Point2f(static_cast<float>(p.x()), static_cast<float>(p.y()));
    }
    prev = image;
  }
  ZoomTracks out;
  out.started = start.size();
  for (std::size_t i = 0; i < start.size(); ++i) {
    if (!alive[i]) continue;
    const double tx = centre.x + scale * (start[i].x - centre.x), ty = centre.y + scale * (start[i].y - centre.y);
    out.errors_px.push_back(std::hypot(cur[i].x - tx, cur[i].y - ty));
    out.anchors.push_back(anchors[i]);
  }
  std::sort(out.errors_px.begin(), out.errors_px.end());
  return out;
}

// Frame-to-frame KLT drifts through the zoom and the brightness step (0.67 px median after ten frames); the
// anchored warp models both and stays within a few hundredths of a pixel of the point (median).
TEST(AnchoredPatch, FollowsAZoomAndABrightnessChangeWithoutDrift) {
  const ZoomTracks plain = track_zoom(false);
  const ZoomTracks anchored = track_zoom(true);
  ASSERT_GT(anchored.started, 100u);
  ASSERT_GT(anchored.errors_px.size(), 0.9 * anchored.started);
  ASSERT_FALSE(plain.errors_px.empty());
  EXPECT_LT(test::median(anchored.errors_px), 0.05);
  EXPECT_LT(anchored.errors_px[anchored.errors_px.size() * 9 / 10], 0.2);
  EXPECT_LT(test::median(anchored.errors_px), 0.2 * test::median(plain.errors_px));
  // The warp found the zoom and the gain (the median over features; single patches of the blocky texture
  // leave the affine part loose).
  std::vector<double> zoom, gain;
  for (const PatchAnchor& a : anchored.anchors) {
    zoom.push_back(std::sqrt(a.A.determinant()));
    gain.push_back(a.gain);
  }
  std::sort(zoom.begin(), zoom.end());
  std::sort(gain.begin(), gain.end());
  EXPECT_NEAR(test::median(zoom), std::pow(1.02, 10), 0.02);
  EXPECT_NEAR(test::median(gain), 0.85, 0.02);
}

TEST(AnchoredPatch, GivesUpOnAnotherPlaceAndLeavesTheTrackAsItWas) {
  const cv::Mat first = test::random_texture(752, 480, 5);
  const cv::Mat other = test::random_texture(752, 480, 6);
  PatchAnchor anchor;
  ASSERT_TRUE(make_anchor(first, Eigen::Vector2d(300.4, 200.7), 7, &anchor));
  const PatchAnchor before = anchor;
  Eigen::Vector2d px(300.4, 200.7);
  const ImagePyramid pyramid = build_klt_pyramid(other, FrontendConfig{});
  EXPECT_FALSE(refine_to_anchor(pyramid[0], pyramid[1], AnchorRefinementConfig{}, &px, &anchor));
  EXPECT_EQ(px, Eigen::Vector2d(300.4, 200.7));
  EXPECT_EQ(anchor.A, before.A);
  EXPECT_EQ(anchor.gain, before.gain);
  // A patch that would reach past the border is no anchor.
  EXPECT_FALSE(make_anchor(first, Eigen::Vector2d(5, 200), 7, &anchor));
}

}  // namespace
}  // namespace vilslam
