#pragma once
// Key frames of loop closure (paper, "Lidar enhanced loop closure", Loop detection): a key image (ORB
// features of the left image, their stereo-triangulated points, its bag of words) associated by timestamp
// with a key scan (its dewarped sparse LiDAR features) and the index of the scan's pose in the global graph.
#include <Eigen/Core>
#include <opencv2/core.hpp>

#include <cstddef>
#include <vector>

#include "common/lie.h"
#include "common/types.h"
#include "frontend/camera_model.h"
#include "frontend/frontend_config.h"
#include "lidar/features.h"
#include "loop/vocabulary.h"

namespace vilslam::loop {

struct KeyImage {
  TimeNs t_ns = 0;                          // the stereo pair's time on the IMU clock
  std::vector<Eigen::Vector2d> left_norm;   // undistorted normalized coordinates in C0 of descriptor row i
  cv::Mat descriptors;                      // N x 32 CV_8U ORB of the left image's Shi-Tomasi corners
  std::vector<Vec3> points_C0;              // row i triangulated from its stereo match, in C0; NaN when unmatched
  BowVector bow;                            // of all N descriptors
  double focal_px = 0.0;                    // the left camera's mean focal length (normalized -> pixels)

  std::size_t num_points() const;           // rows with a finite 3D point
};

// Shi-Tomasi + ORB on both images (the frontend's settings), brute-force stereo matching gated by the
// epipolar geometry (frontend/stereo_matcher.h), KLT refinement of the right corner and linear (DLT)
// triangulation with the frontend's depth range and stereo reprojection check, BoW of the left
// descriptors. Deterministic. Throws InputError for images that do not fit the rig (empty, not 8-bit
// grey, wrong size).
KeyImage make_key_image(const StereoFrame& frame, const StereoRig& rig, const FrontendConfig& config,
                        const Vocabulary& vocabulary);

struct KeyFrame {
  std::size_t id = 0;             // position in the loop closer's key frame list
  std::size_t pose_index = 0;     // the key scan's pose in the global pose graph
  TimeNs scan_t_ns = 0;           // the key scan's end, the instant of its LiDAR pose
  KeyImage image;
  SE3 T_L_C0;                     // the key image's left camera (at image.t_ns) in the key scan's frame L
  lidar::FeatureScan features_L;  // the key scan's features dewarped to the scan end, in L
};

// When a mapped scan becomes a key scan: the first one, then whenever the LiDAR pose has moved or turned
// enough since the last key scan (documented in docs/loop.md).
struct KeyFramePolicy {
  double min_translation_m = 1.0;
  double min_rotation_rad = 0.26;      // 15 degrees
  // A robot that comes to rest (slower than stop_max_speed_mps since the previous mapped sweep) after moving
  // at least stop_min_translation_m since the last key frame gets one there: robots park where they started,
  // and the view at rest is the one the first key frame saw. 0 turns it off.
  double stop_min_translation_m = 0.1;
  double stop_max_speed_mps = 0.05;
  double max_image_scan_gap_s = 0.03;  // a key image lies at most this far in time from its key scan's end
  // false: a key frame whose accepted loop (to a key frame of this run) lies within min_translation_m and
  // min_rotation_rad of the candidate is merged into it, not kept: the place is stored already, so the key
  // frames grow with the mapped area, not with the time spent in it. true keeps every key frame.
  bool keep_revisits = false;
};

// Whether the sweep at T_W_L is a new key scan, after the last key scan at T_W_L_last_key; the previous
// mapped sweep was at T_W_L_prev, dt_s earlier.
bool is_new_key_frame(const SE3& T_W_L_last_key, const SE3& T_W_L_prev, const SE3& T_W_L, double dt_s,
                      const KeyFramePolicy& policy);

}  // namespace vilslam::loop
