#include "frontend/frontend.h"

#include <opencv2/imgproc.hpp>
#include <string>

#include "common/error.h"
#include "frontend/corner_extractor.h"
#include "frontend/outlier_rejection.h"
#include "frontend/stereo_matcher.h"

namespace vilslam {
namespace {

Eigen::Vector2d to_eigen(const cv::Point2f& p) { return {p.x, p.y}; }
cv::Point2f to_cv(const Eigen::Vector2d& v) { return {static_cast<float>(v.x()), static_cast<float>(v.y())}; }

void check_image(const cv::Mat& image, const CameraIntrinsics& cam, const std::string& source, const char* name) {
  if (image.empty()) throw InputError(source, std::string(name) + " image is empty");
  if (image.type() != CV_8UC1) throw InputError(source, std::string(name) + " image is not 8-bit grey");
  if (image.cols != cam.width_px || image.rows != cam.height_px) {
    throw InputError(source, std::string(name) + " image is " + std::to_string(image.cols) + "x" +
                                 std::to_string(image.rows) + ", calibration says " + std::to_string(cam.width_px) +
                                 "x" + std::to_string(cam.height_px));
  }
}

DescribedFeatures describe(const cv::Mat& image, std::vector<cv::Point2f>* corners, const CameraModel& camera,
                           const FrontendConfig& config) {
  DescribedFeatures features;
  features.descriptors = describe_corners(image, corners, config);
  features.xy.reserve(corners->size());
  for (const cv::Point2f& c : *corners) features.xy.push_back(camera.pixel_to_normalized(to_eigen(c)));
  return features;
}

// Both images after CLAHE (FrontendConfig::clahe_clip_limit; the pair itself when off).
StereoFrame equalized(const StereoFrame& frame, const FrontendConfig& config) {
  if (config.clahe_clip_limit <= 0) return frame;
  const cv::Ptr<cv::CLAHE> clahe =
      cv::createCLAHE(config.clahe_clip_limit, cv::Size(config.clahe_tiles, config.clahe_tiles));
  StereoFrame out;
  out.t_ns = frame.t_ns;
  clahe->apply(frame.left, out.left);
  clahe->apply(frame.right, out.right);
  return out;
}

}  // namespace

Frontend::Frontend(const RigCalibration& calib, const FrontendConfig& config)
    : config_(config), rig_(make_stereo_rig(calib)), devignetting_(calib, config.vignetting_samples) {
  validate_frontend_config(config, "frontend config");
}

FrontendOutput Frontend::process(const StereoFrame& frame) {
  const std::string source = "stereo pair t_ns=" + std::to_string(frame.t_ns);
  check_image(frame.left, rig_.cam0.intrinsics(), source, "left");
  check_image(frame.right, rig_.cam1.intrinsics(), source, "right");
  if (initialized_ && frame.t_ns <= prev_t_ns_) {
    throw InputError(source, "not after the previous pair (t_ns=" + std::to_string(prev_t_ns_) + ")");
  }
  stats_ = FrontendStats{};
  StereoFrame devignetted = devignetting_.apply(frame);
  StereoFrame input = equalized(devignetted, config_);
  ImagePyramid left = build_klt_pyramid(input.left, config_);
  ImagePyramid right = build_klt_pyramid(input.right, config_);
  std::vector<Track> tracks;
  if (initialized_) tracks = track_previous(left, right, devignetted);
  FrontendOutput output;
  output.t_ns = frame.t_ns;
  output.tracked = static_cast<int>(tracks.size());
  if (output.tracked < config_.min_tracked_matches) {
    const std::vector<Track> fresh = extract_new(input, left, right, tracks);
    output.extracted = static_cast<int>(fresh.size());
    tracks.insert(tracks.end(), fresh.begin(), fresh.end());
  }
  output.matches.reserve(tracks.size());
  for (const Track& t : tracks) output.matches.push_back(t.match);
  tracks_ = std::move(tracks);
  const StereoDevignetting::RoundEnd round_end = devignetting_.end_round_if_ready();
  stats_.vignetting_rejected = round_end == StereoDevignetting::RoundEnd::kRejected;
  if (round_end == StereoDevignetting::RoundEnd::kFitted) {
    stats_.vignetting_fitted = true;
    // The next pair is tracked from this one: both corrected alike.
    devignetted = devignetting_.apply(frame);
    input = equalized(devignetted, config_);
    left = build_klt_pyramid(input.left, config_);
    right = build_klt_pyramid(input.right, config_);
  }
  prev_devignetted_ = StereoFrame{};
  if (devignetting_.collecting()) prev_devignetted_ = {frame.t_ns, devignetted.left.clone(), devignetted.right.clone()};
  prev_left_ = std::move(left);
  prev_right_ = std::move(right);
  prev_t_ns_ = frame.t_ns;
  initialized_ = true;
  return output;
}

std::vector<Frontend::Track> Frontend::track_previous(const ImagePyramid& left, const ImagePyramid& right,
                                                      const StereoFrame& devignetted) {
  std::vector<cv::Point2f> prev_left_px, left_px;
  prev_left_px.reserve(tracks_.size());
  for (const Track& t : tracks_) prev_left_px.push_back(to_cv(t.match.left_px));
  std::vector<bool> left_ok;
  track_klt(prev_left_, left, prev_left_px, config_, &left_px, &left_ok);
  // A track needs both images: the right image tracks only what the left one kept (LK tracks each point
  // on its own, so the others would not change).
  std::vector<std::size_t> left_kept;
  std::vector<cv::Point2f> prev_right_px, right_px;
  for (std::size_t i = 0; i < tracks_.size(); ++i) {
    if (!left_ok[i]) continue;
    left_kept.push_back(i);
    prev_right_px.push_back(to_cv(tracks_[i].match.right_px));
  }
  std::vector<bool> right_ok;
  track_klt(prev_right_, right, prev_right_px, config_, &right_px, &right_ok);
  if (devignetting_.collecting()) {
    devignetting_.add_step(0, prev_devignetted_.left, devignetted.left, prev_left_px, left_px, left_ok);
    devignetting_.add_step(1, prev_devignetted_.right, devignetted.right, prev_right_px, right_px, right_ok);
  }
  stats_.klt_lost = static_cast<int>(tracks_.size() - left_kept.size());
  std::vector<Track> tracked;
  std::vector<Vec3> p_C0prev;
  for (std::size_t k = 0; k < left_kept.size(); ++k) {
    if (!right_ok[k]) {
      ++stats_.klt_lost;
      continue;
    }
    const std::size_t i = left_kept[k];
    Track t = tracks_[i];
    t.match.left_px = to_eigen(left_px[i]);
    t.match.right_px = to_eigen(right_px[k]);
    ++t.match.age_frames;
    if (!stereo_check(&t)) {
      ++stats_.stereo_rejected;
      continue;
    }
    tracked.push_back(t);
    p_C0prev.push_back(tracks_[i].p_C0);
  }
  reject_temporal_outliers(&tracked, p_C0prev);
  return tracked;
}

void Frontend::reject_temporal_outliers(std::vector<Track>* tracks, const std::vector<Vec3>& p_C0prev) {
  std::vector<Eigen::Vector2d> xy_cur;
  for (const Track& t : *tracks) xy_cur.push_back(t.match.left_norm);
  const MotionEstimate motion = estimate_motion_pnp(p_C0prev, xy_cur, rig_.cam0.focal_px(), config_);
  stats_.motion_valid = motion.valid;
  if (!motion.valid) return;
  stats_.T_C0cur_C0prev = motion.T_C0cur_C0prev;
  std::vector<Track> kept;
  for (std::size_t i = 0; i < tracks->size(); ++i) {
    const Track& t = (*tracks)[i];
    // Temporal check: the previous pair's point moved by the estimated motion, reprojected into both images.
    const Vec3 p_C0 = motion.T_C0cur_C0prev * p_C0prev[i];
    if (stereo_reprojection_error_px(rig_, p_C0, t.match.left_px, t.match.right_px) >
        config_.max_temporal_reprojection_px) {
      ++stats_.temporal_rejected;
      continue;
    }
    kept.push_back(t);
  }
  *tracks = std::move(kept);
}

std::vector<Frontend::Track> Frontend::extract_new(const StereoFrame& frame, const ImagePyramid& left_pyramid,
                                                   const ImagePyramid& right_pyramid,
                                                   const std::vector<Track>& existing) {
  std::vector<cv::Point2f> existing_left, existing_right;
  for (const Track& t : existing) {
    existing_left.push_back(to_cv(t.match.left_px));
    existing_right.push_back(to_cv(t.match.right_px));
  }
  std::vector<cv::Point2f> corners_left =
      eliminate_near_features(detect_corners(frame.left, config_), existing_left, config_.elimination_distance_px);
  std::vector<cv::Point2f> corners_right =
      eliminate_near_features(detect_corners(frame.right, config_), existing_right, config_.elimination_distance_px);
  stats_.corners_left = static_cast<int>(corners_left.size());
  stats_.corners_right = static_cast<int>(corners_right.size());
  const DescribedFeatures features_left = describe(frame.left, &corners_left, rig_.cam0, config_);
  const DescribedFeatures features_right = describe(frame.right, &corners_right, rig_.cam1, config_);
  std::vector<Track> matched;
  for (const IndexPair& pair :
       match_stereo(features_left, features_right, rig_.T_C1_C0, rig_.cam1.focal_px(), config_)) {
    Track t;
    t.match.left_px = to_eigen(corners_left[pair.left]);
    t.match.right_px = to_eigen(corners_right[pair.right]);
    matched.push_back(t);
  }
  std::vector<Track> fresh;
  for (Track& t : refine_right(left_pyramid, right_pyramid, std::move(matched))) {
    if (!stereo_check(&t)) {
      ++stats_.stereo_rejected;
      continue;
    }
    t.match.track_id = next_track_id_++;
    fresh.push_back(t);
  }
  return fresh;
}

std::vector<Frontend::Track> Frontend::refine_right(const ImagePyramid& left, const ImagePyramid& right,
                                                    std::vector<Track> fresh) {
  if (config_.max_stereo_refinement_px <= 0) return fresh;
  std::vector<cv::Point2f> left_px, right_px;
  for (const Track& t : fresh) {
    left_px.push_back(to_cv(t.match.left_px));
    right_px.push_back(to_cv(t.match.right_px));
  }
  // Independent corners of the two images may sit a pixel or two apart on the same structure; KLT from
  // the left corner, started at the matched right corner, finds the right pixel of the same point.
  std::vector<bool> ok;
  refine_klt(left, right, left_px, config_, &right_px, &ok);
  std::vector<Track> refined;
  for (std::size_t i = 0; i < fresh.size(); ++i) {
    const Eigen::Vector2d moved_to = to_eigen(right_px[i]);
    if (!ok[i] || (moved_to - fresh[i].match.right_px).norm() > config_.max_stereo_refinement_px) {
      ++stats_.refine_rejected;
      continue;
    }
    fresh[i].match.right_px = moved_to;
    refined.push_back(fresh[i]);
  }
  return refined;
}

bool Frontend::stereo_check(Track* track) const {
  StereoMatch& m = track->match;
  m.left_norm = rig_.cam0.pixel_to_normalized(m.left_px);
  m.right_norm = rig_.cam1.pixel_to_normalized(m.right_px);
  if (!triangulate_stereo(m.left_norm, m.right_norm, rig_.T_C1_C0, &track->p_C0)) return false;
  const double depth_m = track->p_C0.z();
  if (depth_m < config_.min_depth_m || depth_m > config_.max_depth_m) return false;
  return stereo_reprojection_error_px(rig_, track->p_C0, m.left_px, m.right_px) <= config_.max_stereo_reprojection_px;
}

}  // namespace vilslam
