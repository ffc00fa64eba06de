#pragma once
// Brute-force ORB matching between two images without geometry (loop detection: the left key image
// against a candidate's descriptors): Hamming-nearest, absolute and ratio thresholds, mutual check.
#include <opencv2/core.hpp>
#include <vector>

namespace vilslam::loop {

struct DescriptorMatch {
  int query = 0;  // row of the query descriptors
  int train = 0;  // row of the train descriptors
};

struct DescriptorMatchConfig {
  int max_distance = 60;     // Hamming, out of 256 bits
  double ratio_test = 0.75;  // best / second-best distance must be below this
};

// Query rows whose nearest train row is under max_distance, passes the ratio test and whose own nearest
// query row is the same (mutual). Ordered by query row; deterministic (ties resolve to the lower row).
std::vector<DescriptorMatch> match_descriptors(const cv::Mat& query, const cv::Mat& train,
                                               const DescriptorMatchConfig& config);

}  // namespace vilslam::loop
