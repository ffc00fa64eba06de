#pragma once
// The visual frontend's output: stereo matches of one stereo pair, the VIO's visual measurements.
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "common/time.h"

namespace vilslam {

struct StereoMatch {
  std::uint64_t track_id = 0;        // the same physical feature keeps its id while it is tracked
  Eigen::Vector2d left_px = Eigen::Vector2d::Zero();     // distorted pixel in cam0
  Eigen::Vector2d right_px = Eigen::Vector2d::Zero();    // distorted pixel in cam1
  Eigen::Vector2d left_norm = Eigen::Vector2d::Zero();   // undistorted normalized coordinates (x/z, y/z) in C0
  Eigen::Vector2d right_norm = Eigen::Vector2d::Zero();  // undistorted normalized coordinates in C1
  int age_frames = 0;                // 0 when extracted in this pair
};

struct FrontendOutput {
  TimeNs t_ns = 0;
  std::vector<StereoMatch> matches;
  int tracked = 0;    // matches carried over from the previous pair
  int extracted = 0;  // new matches from Shi-Tomasi + ORB + brute-force stereo matching
};

}  // namespace vilslam
