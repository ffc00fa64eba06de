#pragma once
// Brute-force ORB stereo matching, gated by the epipolar geometry and a depth range.
#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <vector>

#include "common/lie.h"
#include "frontend/frontend_config.h"

namespace vilslam {

// Features of one image: undistorted normalized coordinates and their ORB descriptors (row i <-> i).
struct DescribedFeatures {
  std::vector<Eigen::Vector2d> xy;
  cv::Mat descriptors;
};

struct IndexPair {
  int left = 0;
  int right = 0;
};

// Left/right index pairs, ordered by left index. A right feature is a candidate for a left one when it
// lies within max_epipolar_distance_px (measured with focal_right_px) of the segment that the left ray
// between min_depth_m and max_depth_m projects to in C1. Among candidates the Hamming-nearest wins when
// it is under max_descriptor_distance, passes the ratio test and (cross_check) is mutual.
std::vector<IndexPair> match_stereo(const DescribedFeatures& left, const DescribedFeatures& right,
                                    const SE3& T_C1_C0, double focal_right_px, const FrontendConfig& config);

}  // namespace vilslam
