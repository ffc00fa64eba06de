#pragma once
// The visual frontend (paper, "Visual frontend"): KLT frame-to-frame tracking of the previous stereo
// matches in both images, Shi-Tomasi + ORB stereo matching of new features when too few survive, and
// stereo / temporal outlier rejection on average reprojection errors. The only stateful object here.
#include <cstdint>
#include <vector>

#include "common/calibration.h"
#include "common/types.h"
#include "frontend/camera_model.h"
#include "frontend/frontend_config.h"
#include "frontend/klt_tracker.h"
#include "frontend/stereo_match.h"
#include "frontend/stereo_devignetting.h"

namespace vilslam {

// What happened to the matches of the last pair (for logs, tests and tuning).
struct FrontendStats {
  int klt_lost = 0;           // previous matches not tracked in both images
  int stereo_rejected = 0;    // tracked or new matches over the stereo reprojection threshold
  int refine_rejected = 0;    // new matches whose left -> right KLT refinement failed or moved too far
  int temporal_rejected = 0;  // tracked matches inconsistent with the frame-to-frame motion
  bool motion_valid = false;  // the PnP motion estimate was available for the temporal check
  SE3 T_C0cur_C0prev;         // that estimate (left camera, previous pair to this one) when motion_valid
  int corners_left = 0;       // Shi-Tomasi corners surviving elimination (0 when no extraction ran)
  int corners_right = 0;
  bool vignetting_fitted = false;    // a round of the vignetting self-calibration ended on this pair
  bool vignetting_rejected = false;  // its fit was implausible and the self-calibration stopped
};

class Frontend {
 public:
  // Throws InputError when the calibration or the config is unusable.
  Frontend(const RigCalibration& calib, const FrontendConfig& config = {});

  // Processes the next stereo pair (8-bit grey, the calibrated size; otherwise InputError).
  FrontendOutput process(const StereoFrame& frame);

  const FrontendStats& last_stats() const { return stats_; }
  const StereoRig& rig() const { return rig_; }
  // The fitted vignetting of camera 0 or 1 (FrontendConfig::vignetting_samples); nullptr until fitted.
  const VignettingModel* vignetting(int camera) const { return devignetting_.model(camera); }

 private:
  struct Track {
    StereoMatch match;
    Vec3 p_C0 = Vec3::Zero();  // triangulated in this pair's left camera frame
  };

  // Also feeds the vignetting self-calibration with each image's KLT steps while it collects (devignetted =
  // this pair as corrected so far, before CLAHE).
  std::vector<Track> track_previous(const ImagePyramid& left, const ImagePyramid& right,
                                    const StereoFrame& devignetted);
  void reject_temporal_outliers(std::vector<Track>* tracks, const std::vector<Vec3>& p_C0prev);
  std::vector<Track> extract_new(const StereoFrame& frame, const ImagePyramid& left, const ImagePyramid& right,
                                 const std::vector<Track>& existing);
  // Moves each new match's right pixel onto its left corner's appearance (KLT left -> right).
  std::vector<Track> refine_right(const ImagePyramid& left, const ImagePyramid& right, std::vector<Track> fresh);
  // Fills the normalized coordinates and the 3D point; false when the stereo check rejects the match.
  bool stereo_check(Track* track) const;

  FrontendConfig config_;
  StereoRig rig_;
  StereoDevignetting devignetting_;
  StereoFrame prev_devignetted_;  // kept while the vignetting self-calibration collects
  std::vector<Track> tracks_;
  ImagePyramid prev_left_, prev_right_;
  std::uint64_t next_track_id_ = 0;
  bool initialized_ = false;
  TimeNs prev_t_ns_ = 0;
  FrontendStats stats_;
};

}  // namespace vilslam
