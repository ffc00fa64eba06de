#pragma once
// Every tuning value of the visual frontend, with defaults fit for EuRoC-like 752x480 stereo.
#include <cstdint>
#include <string>

#include "common/yaml_config.h"

namespace vilslam {

struct FrontendConfig {
  // Contrast-limited adaptive histogram equalization of both images before anything else (cv::CLAHE, as
  // VINS-Mono's `equalize`): evens out vignetting and exposure changes across the image. Clip limit > 0
  // turns it on (3 in VINS-Mono); the image is cut into clahe_tiles x clahe_tiles tiles.
  double clahe_clip_limit = 0;
  int clahe_tiles = 8;
  // Vignetting self-calibration (frontend/vignetting.h): the frontend fits each lens's radial falloff to the
  // brightness of its KLT tracks, and once each camera has this many informative samples it divides every
  // later image by the fitted falloff (before CLAHE). 0 turns it off. On by default since 2026-11-29: it passed
  // a rule written before its runs on eight fresh tuning routes (docs/evaluation.md, "Fresh routes of every preset").
  int vignetting_samples = 2000;
  // Extraction runs when fewer tracked stereo matches than this survive (and on the first pair).
  int min_tracked_matches = 150;
  // Shi-Tomasi (cv::goodFeaturesToTrack) per image.
  int max_corners = 600;
  double corner_quality = 0.003;
  double corner_min_distance_px = 8;
  int corner_block_size = 3;
  int corner_subpix_half_window_px = 3;  // cv::cornerSubPix refinement; 0 keeps integer corners
  // New corners closer than this to an existing (tracked) feature of the same image are eliminated.
  double elimination_distance_px = 8;
  // Pyramidal KLT (cv::calcOpticalFlowPyrLK).
  int klt_window_px = 21;
  int klt_pyramid_levels = 3;
  int klt_max_iterations = 30;
  double klt_epsilon = 0.01;
  // Forward-backward check: a track survives when tracking back lands this close to its start.
  double klt_max_forward_backward_px = 1.0;
  // When > 0, the forward track's finest level is run once more with this (odd, smaller) window, started from
  // the pyramidal result; 0 keeps klt_window_px at every level. 11 with the global graph's bearing_min_step_m
  // 0.05 (decided together, 2026-12-07; docs/frontend.md, "A small final KLT window").
  int klt_final_window_px = 11;
  // ORB descriptors (cv::ORB::compute) on the surviving corners; corners nearer the border are dropped.
  int orb_patch_size = 31;
  // Brute-force stereo matching.
  int max_descriptor_distance = 60;     // Hamming, out of 256 bits
  double ratio_test = 0.75;             // best / second-best distance
  bool cross_check = true;              // the right corner's best left match must be the same corner
  double max_epipolar_distance_px = 2.0;
  double min_depth_m = 0.3;
  double max_depth_m = 40.0;
  // KLT (left -> right, started at the matched corner) refines new matches; a match whose refinement
  // fails or moves farther than this is dropped. 0 disables the refinement.
  double max_stereo_refinement_px = 3.0;
  // Outlier rejection on average reprojection errors (left and right image).
  double max_stereo_reprojection_px = 1.5;
  double max_temporal_reprojection_px = 3.0;
  // Frame-to-frame motion for the temporal check: PnP RANSAC on the previous pair's 3D points.
  int pnp_min_points = 10;
  int pnp_ransac_iterations = 100;
  double pnp_ransac_threshold_px = 2.0;
  std::uint64_t ransac_seed = 1;
};

// The YAML keys of the config (the field names), bound to c's fields: the `frontend:` section of a run
// config (pipeline/run_config.h). Validate after reading.
YamlFields frontend_yaml_fields(FrontendConfig& c);

// Throws InputError(source, ...) when a value is out of range.
void validate_frontend_config(const FrontendConfig& config, const std::string& source);

}  // namespace vilslam
