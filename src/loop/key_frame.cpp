#include "loop/key_frame.h"

#include <cmath>
#include <limits>
#include <string>

#include "common/error.h"
#include "frontend/klt_tracker.h"
#include "frontend/outlier_rejection.h"
#include "frontend/stereo_matcher.h"
#include "loop/image_descriptors.h"

namespace vilslam::loop {
namespace {

void check_image(const cv::Mat& image, const CameraIntrinsics& cam, const std::string& source, const char* name) {
  if (image.empty() || image.type() != CV_8UC1) {
    throw InputError(source, std::string(name) + " key image is empty or not 8-bit grey");
  }
  if (image.cols != cam.width_px || image.rows != cam.height_px) {
    throw InputError(source, std::string(name) + " key image is " + std::to_string(image.cols) + "x" +
                                 std::to_string(image.rows) + ", calibration says " + std::to_string(cam.width_px) +
                                 "x" + std::to_string(cam.height_px));
  }
}

// Shi-Tomasi corners of a whole image, their ORB descriptors, pixels and undistorted normalized coordinates.
struct Described {
  std::vector<cv::Point2f> px;
  DescribedFeatures features;
};

Described describe_whole_image(const cv::Mat& image, const CameraModel& camera, const FrontendConfig& config) {
  Described d;
  d.features.descriptors = describe_image(image, config, &d.px);
  for (const cv::Point2f& c : d.px) d.features.xy.push_back(camera.pixel_to_normalized({c.x, c.y}));
  return d;
}

}  // namespace

std::size_t KeyImage::num_points() const {
  std::size_t n = 0;
  for (const Vec3& p : points_C0) n += p.allFinite() ? 1 : 0;
  return n;
}

KeyImage make_key_image(const StereoFrame& frame, const StereoRig& rig, const FrontendConfig& config,
                        const Vocabulary& vocabulary) {
  const std::string source = "key image t_ns=" + std::to_string(frame.t_ns);
  check_image(frame.left, rig.cam0.intrinsics(), source, "left");
  check_image(frame.right, rig.cam1.intrinsics(), source, "right");
  const Described left = describe_whole_image(frame.left, rig.cam0, config);
  const Described right = describe_whole_image(frame.right, rig.cam1, config);

  KeyImage key;
  key.t_ns = frame.t_ns;
  key.focal_px = rig.cam0.focal_px();
  key.left_norm = left.features.xy;
  key.descriptors = left.features.descriptors;
  key.points_C0.assign(left.px.size(), Vec3::Constant(std::numeric_limits<double>::quiet_NaN()));
  key.bow = vocabulary.transform(key.descriptors);

  const std::vector<IndexPair> pairs =
      match_stereo(left.features, right.features, rig.T_C1_C0, rig.cam1.focal_px(), config);
  // Independent corners of the two images may sit a pixel apart on the same structure: as the frontend
  // does, KLT from the left corner, started at the matched right corner, finds the right pixel.
  std::vector<cv::Point2f> left_px, right_px;
  for (const IndexPair& p : pairs) {
    left_px.push_back(left.px[p.left]);
    right_px.push_back(right.px[p.right]);
  }
  std::vector<bool> refined(pairs.size(), true);
  if (config.max_stereo_refinement_px > 0 && !pairs.empty()) {
    const std::vector<cv::Point2f> matched_right_px = right_px;
    refine_klt(build_klt_pyramid(frame.left, config), build_klt_pyramid(frame.right, config), left_px, config,
               &right_px, &refined);
    for (std::size_t k = 0; k < pairs.size(); ++k) {
      refined[k] = refined[k] && cv::norm(right_px[k] - matched_right_px[k]) <= config.max_stereo_refinement_px;
    }
  }
  for (std::size_t k = 0; k < pairs.size(); ++k) {
    if (!refined[k]) continue;
    const Eigen::Vector2d px0(left_px[k].x, left_px[k].y), px1(right_px[k].x, right_px[k].y);
    Vec3 p_C0;
    if (!triangulate_stereo(left.features.xy[pairs[k].left], rig.cam1.pixel_to_normalized(px1), rig.T_C1_C0, &p_C0)) {
      continue;
    }
    if (p_C0.z() < config.min_depth_m || p_C0.z() > config.max_depth_m) continue;
    if (stereo_reprojection_error_px(rig, p_C0, px0, px1) > config.max_stereo_reprojection_px) continue;
    key.points_C0[pairs[k].left] = p_C0;
  }
  return key;
}

bool is_new_key_frame(const SE3& T_W_L_last_key, const SE3& T_W_L_prev, const SE3& T_W_L, double dt_s,
                      const KeyFramePolicy& policy) {
  const SE3 T_last_cur = T_W_L_last_key.inverse() * T_W_L;
  const double moved_m = T_last_cur.translation().norm();
  if (moved_m >= policy.min_translation_m || so3::log(T_last_cur.quat()).norm() >= policy.min_rotation_rad) return true;
  const bool stopped = dt_s > 0.0 && (T_W_L.translation() - T_W_L_prev.translation()).norm() / dt_s < policy.stop_max_speed_mps;
  return policy.stop_min_translation_m > 0.0 && stopped && moved_m >= policy.stop_min_translation_m;
}

}  // namespace vilslam::loop
