#include "frontend/stereo_matcher.h"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <limits>

namespace vilslam {
namespace {

constexpr int kNoCandidate = std::numeric_limits<int>::max();

int hamming_256(const uchar* a, const uchar* b) {
  int bits = 0;
  for (int k = 0; k < 32; k += 8) {
    std::uint64_t wa, wb;
    std::memcpy(&wa, a + k, 8);
    std::memcpy(&wb, b + k, 8);
    bits += __builtin_popcountll(wa ^ wb);
  }
  return bits;
}

double point_segment_distance(const Eigen::Vector2d& p, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  const Eigen::Vector2d ab = b - a;
  const double len_sq = ab.squaredNorm();
  const double s = len_sq > 0 ? std::clamp((p - a).dot(ab) / len_sq, 0.0, 1.0) : 0.0;
  return (a + s * ab - p).norm();
}

// Index of the smallest entry of `distances` (stride apart, count of them) and whether it passes the
// absolute and ratio thresholds.
int best_passing(const int* distances, int count, int stride, const FrontendConfig& config) {
  int best = kNoCandidate, second = kNoCandidate, best_index = -1;
  for (int k = 0; k < count; ++k) {
    const int d = distances[k * stride];
    if (d < best) {
      second = best;
      best = d;
      best_index = k;
    } else if (d < second) {
      second = d;
    }
  }
  if (best_index < 0 || best > config.max_descriptor_distance) return -1;
  if (second != kNoCandidate && best >= config.ratio_test * second) return -1;
  return best_index;
}

}  // namespace

std::vector<IndexPair> match_stereo(const DescribedFeatures& left, const DescribedFeatures& right,
                                    const SE3& T_C1_C0, double focal_right_px, const FrontendConfig& config) {
  const int n_left = static_cast<int>(left.xy.size()), n_right = static_cast<int>(right.xy.size());
  std::vector<IndexPair> pairs;
  if (n_left == 0 || n_right == 0) return pairs;
  CV_Assert(left.descriptors.cols == 32 && right.descriptors.cols == 32);
  // distances(i, j): Hamming distance of a geometrically admissible pair, kNoCandidate otherwise.
  std::vector<int> distances(static_cast<std::size_t>(n_left) * n_right, kNoCandidate);
  const double max_offset = config.max_epipolar_distance_px / focal_right_px;
  for (int i = 0; i < n_left; ++i) {
    const Vec3 ray_C1 = T_C1_C0.rotation() * left.xy[i].homogeneous();
    const Vec3 near_C1 = ray_C1 * config.min_depth_m + T_C1_C0.translation();
    const Vec3 far_C1 = ray_C1 * config.max_depth_m + T_C1_C0.translation();
    if (near_C1.z() <= 0 || far_C1.z() <= 0) continue;
    const Eigen::Vector2d a = near_C1.hnormalized(), b = far_C1.hnormalized();
    const uchar* desc_left = left.descriptors.ptr<uchar>(i);
    for (int j = 0; j < n_right; ++j) {
      if (point_segment_distance(right.xy[j], a, b) > max_offset) continue;
      distances[static_cast<std::size_t>(i) * n_right + j] = hamming_256(desc_left, right.descriptors.ptr<uchar>(j));
    }
  }
  for (int i = 0; i < n_left; ++i) {
    const int j = best_passing(&distances[static_cast<std::size_t>(i) * n_right], n_right, 1, config);
    if (j < 0) continue;
    if (config.cross_check && best_passing(&distances[j], n_left, n_right, config) != i) continue;
    pairs.push_back({i, j});
  }
  return pairs;
}

}  // namespace vilslam
