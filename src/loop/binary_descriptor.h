#pragma once
// A 256-bit ORB descriptor as a value (one 32-byte row of OpenCV's CV_8U descriptor matrix) and the
// Hamming distance between two of them.
#include <array>
#include <cstdint>
#include <cstring>
#include <opencv2/core.hpp>
#include <vector>

namespace vilslam {

using OrbDescriptor = std::array<std::uint8_t, 32>;

inline int hamming_distance(const OrbDescriptor& a, const OrbDescriptor& b) {
  int bits = 0;
  for (std::size_t i = 0; i < a.size(); i += 8) {
    std::uint64_t wa, wb;
    std::memcpy(&wa, a.data() + i, 8);
    std::memcpy(&wb, b.data() + i, 8);
    bits += __builtin_popcountll(wa ^ wb);
  }
  return bits;
}

// The rows of an N x 32 CV_8U matrix; throws std::invalid_argument for any other shape or type.
std::vector<OrbDescriptor> descriptor_rows(const cv::Mat& descriptors);

}  // namespace vilslam
