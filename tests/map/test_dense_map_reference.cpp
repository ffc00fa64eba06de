// DenseMap against a reference: one std::map from voxel key to (running mean, count), the map's original
// algorithm (one hash table entry per voxel). points() must match it bit for bit for every min_hits.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <random>

#include "map/dense_map.h"

namespace vilslam::map {
namespace {

using Eigen::Vector3f;

class ReferenceMap {
 public:
  explicit ReferenceMap(double voxel_size_m) : voxel_size_m_(voxel_size_m) {}

  void insert(const std::vector<Vector3f>& points_W) {
    for (const Vector3f& p : points_W) {
      if (!p.allFinite()) continue;
      std::uint64_t key = 0;
      bool in_range = true;
      for (int axis = 0; axis < 3; ++axis) {
        const double index = std::floor(static_cast<double>(p[axis]) / voxel_size_m_) + 1048576.0;  // 2^20 bias
        in_range = in_range && index >= 0.0 && index <= 2097151.0;
        key = (key << 21) | (in_range ? static_cast<std::uint64_t>(index) : 0);
      }
      if (!in_range) continue;
      Voxel& v = voxels_[key];
      ++v.count;
      v.mean_W += (p - v.mean_W) / static_cast<float>(v.count);
    }
  }

  std::vector<Vector3f> points(std::uint32_t min_hits) const {
    std::vector<Vector3f> out;
    for (const auto& [key, v] : voxels_) {
      if (v.count >= min_hits) out.push_back(v.mean_W);
    }
    return out;
  }

  std::size_t num_voxels() const { return voxels_.size(); }

 private:
  struct Voxel {
    Vector3f mean_W = Vector3f::Zero();
    std::uint32_t count = 0;
  };
  double voxel_size_m_;
  std::map<std::uint64_t, Voxel> voxels_;
};

bool bit_identical(const std::vector<Vector3f>& a, const std::vector<Vector3f>& b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(Vector3f)) == 0);
}

// Noisy points on a few planes crossing block boundaries and the origin, in several batches, with repeated
// hits per voxel, plus non-finite and out-of-range points.
std::vector<std::vector<Vector3f>> surface_batches() {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(-0.6f, 0.6f);
  std::normal_distribution<float> noise_m(0.0f, 0.004f);
  std::vector<std::vector<Vector3f>> batches(5);
  for (std::size_t batch = 0; batch < batches.size(); ++batch) {
    for (int i = 0; i < 60000; ++i) {
      const float a = u(rng), b = u(rng), n = noise_m(rng);
      switch (i % 3) {
        case 0: batches[batch].emplace_back(a, b, n - 0.3f); break;
        case 1: batches[batch].emplace_back(n + 0.17f, a, b); break;
        default: batches[batch].emplace_back(a, 0.7f * b + n, 0.7f * b - n); break;
      }
    }
    batches[batch].emplace_back(std::numeric_limits<float>::quiet_NaN(), 0.0f, 0.0f);
    batches[batch].emplace_back(2e4f, 0.0f, 0.0f);
  }
  return batches;
}

TEST(DenseMapReference, PointsBitIdenticalToOneEntryPerVoxelReference) {
  for (double voxel_size_m : {0.01, 0.013}) {
    DenseMap map(voxel_size_m);
    ReferenceMap reference(voxel_size_m);
    for (const auto& batch : surface_batches()) {
      map.insert(batch);
      reference.insert(batch);
    }
    ASSERT_EQ(map.num_voxels(), reference.num_voxels());
    ASSERT_GT(map.num_voxels(), 20000u);
    for (std::uint32_t min_hits : {0u, 1u, 2u, 3u, 5u, 8u}) {
      EXPECT_TRUE(bit_identical(map.points(min_hits), reference.points(min_hits))) << voxel_size_m << " " << min_hits;
    }
  }
}

TEST(DenseMapReference, CountsBeyondSixteenBitsStayExact) {
  DenseMap map(0.01);
  ReferenceMap reference(0.01);
  std::vector<Vector3f> points;
  for (int i = 0; i < 70000; ++i) points.emplace_back(0.001f + 1e-7f * static_cast<float>(i % 97), -0.005f, 0.009f);
  points.emplace_back(0.5f, 0.5f, 0.5f);
  map.insert(points);
  reference.insert(points);
  EXPECT_EQ(map.points(70000).size(), 1u);
  EXPECT_TRUE(map.points(70001).empty());
  for (std::uint32_t min_hits : {1u, 70000u}) EXPECT_TRUE(bit_identical(map.points(min_hits), reference.points(min_hits)));
}

}  // namespace
}  // namespace vilslam::map
