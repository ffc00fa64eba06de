#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "frontend/camera_model.h"
#include "frontend/corner_extractor.h"
#include "frontend/stereo_matcher.h"
#include "synthetic_stereo.h"
#include "test_util.h"

namespace vilslam {
namespace {

struct StereoScene {
  RigCalibration calib = test::pinhole_stereo_rig();
  test::TexturedPlane plane = test::facing_plane(3.0, 0.45, 21);  // disparity varies across the image
  cv::Mat left, right;
  StereoScene() {
    left = test::render_plane(plane, calib.cam0, calib.T_I_C0);
    right = test::render_plane(plane, calib.cam1, calib.T_I_C1);
  }
};

struct MatchingResult {
  std::vector<cv::Point2f> left_px, right_px;
  std::vector<IndexPair> pairs;
};

MatchingResult detect_and_match(const StereoScene& scene, const FrontendConfig& config) {
  const StereoRig rig = make_stereo_rig(scene.calib);
  MatchingResult r;
  r.left_px = detect_corners(scene.left, config);
  r.right_px = detect_corners(scene.right, config);
  const auto describe = [&config](const cv::Mat& image, std::vector<cv::Point2f>* px, const CameraModel& cam) {
    DescribedFeatures f;
    f.descriptors = describe_corners(image, px, config);
    for (const cv::Point2f& p : *px) f.xy.push_back(cam.pixel_to_normalized({p.x, p.y}));
    return f;
  };
  const DescribedFeatures left = describe(scene.left, &r.left_px, rig.cam0);
  const DescribedFeatures right = describe(scene.right, &r.right_px, rig.cam1);
  r.pairs = match_stereo(left, right, rig.T_C1_C0, rig.cam1.focal_px(), config);
  return r;
}

TEST(StereoMatcher, FindsTheKnownDisparitiesOfASlantedPlane) {
  const StereoScene scene;
  const FrontendConfig config;
  const MatchingResult r = detect_and_match(scene, config);
  ASSERT_GT(r.pairs.size(), 0.5 * r.left_px.size());
  const CameraModel cam(scene.calib.cam0);
  double min_disparity = 1e9, max_disparity = 0;
  int correct = 0;
  std::vector<double> errors_px;
  for (const IndexPair& p : r.pairs) {
    const Eigen::Vector2d left(r.left_px[p.left].x, r.left_px[p.left].y);
    // Ground truth: the left ray meets the plane at depth Z; disparity = f b / Z on this rectified rig.
    const Vec3 p_C0 = scene.plane.intersect(SE3(), cam.pixel_to_normalized(left));
    const double disparity_px = cam.intrinsics().fx * test::kBaselineM / p_C0.z();
    min_disparity = std::min(min_disparity, disparity_px);
    max_disparity = std::max(max_disparity, disparity_px);
    const double measured_px = r.left_px[p.left].x - r.right_px[p.right].x;
    const double error_px = std::hypot(measured_px - disparity_px, r.left_px[p.left].y - r.right_px[p.right].y);
    correct += error_px < 1.0;
    errors_px.push_back(error_px);
  }
  EXPECT_GT(max_disparity - min_disparity, 5.0);  // the scene really tests varying disparities
  // Sub-pixel corners: typically a tenth of a pixel; a few ambiguous textures may match along the line.
  EXPECT_GE(correct, 0.98 * r.pairs.size()) << "of " << r.pairs.size();
  EXPECT_LT(test::median(errors_px), 0.2);
  for (std::size_t k = 1; k < r.pairs.size(); ++k) EXPECT_LT(r.pairs[k - 1].left, r.pairs[k].left);
}

TEST(StereoMatcher, DepthRangeExcludesThePlane) {
  const StereoScene scene;  // the plane is about 2 to 5 m away
  FrontendConfig config;
  const std::size_t all = detect_and_match(scene, config).pairs.size();
  // What remains are look-alike corners of the rectangle texture, accepted only when the true match is gated out.
  config.max_depth_m = 1.5;
  EXPECT_LT(detect_and_match(scene, config).pairs.size(), 0.03 * all);
  config.min_depth_m = 6.0;
  config.max_depth_m = 40.0;
  EXPECT_LT(detect_and_match(scene, config).pairs.size(), 0.03 * all);
}

TEST(StereoMatcher, WrongEpipolarGeometryFindsAlmostNothing) {
  StereoScene scene;
  // Tell the matcher the right camera sits below the left one: the true matches leave the epipolar band.
  scene.calib.T_I_C1 = SE3(Quat::Identity(), Vec3(0, test::kBaselineM, 0));
  const FrontendConfig config;
  const MatchingResult r = detect_and_match(scene, config);
  EXPECT_LT(r.pairs.size(), 0.03 * r.left_px.size());
}

}  // namespace
}  // namespace vilslam
