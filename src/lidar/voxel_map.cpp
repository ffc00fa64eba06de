#include "lidar/voxel_map.h"

#include <algorithm>
#include <cmath>
#include <tsl/robin_set.h>

namespace vilslam::lidar {

namespace {

Eigen::Vector3i floor_key(const Vec3& p, double size) {
  return Eigen::Vector3i(static_cast<int>(std::floor(p.x() / size)), static_cast<int>(std::floor(p.y() / size)),
                         static_cast<int>(std::floor(p.z() / size)));
}

bool key_less(const Eigen::Vector3i& a, const Eigen::Vector3i& b) {
  return std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3);
}

}  // namespace

std::size_t VoxelKeyHash::operator()(const Eigen::Vector3i& v) const {
  return static_cast<std::size_t>((static_cast<std::uint64_t>(v.x()) * 73856093u) ^
                                  (static_cast<std::uint64_t>(v.y()) * 19349669u) ^
                                  (static_cast<std::uint64_t>(v.z()) * 83492791u));
}

VoxelMap::VoxelMap(const VoxelMapConfig& config) : config_(config) {}

Eigen::Vector3i VoxelMap::key_of(const Vec3& p) const { return floor_key(p, config_.voxel_size_m); }

void VoxelMap::insert(const std::vector<Vec3>& points_W) {
  const double min_sq = config_.min_point_spacing_m * config_.min_point_spacing_m;
  for (const Vec3& p : points_W) {
    std::vector<Vec3>& voxel = voxels_[key_of(p)];
    if (static_cast<int>(voxel.size()) >= config_.max_points_per_voxel) continue;
    const bool crowded =
        std::any_of(voxel.begin(), voxel.end(), [&](const Vec3& q) { return (q - p).squaredNorm() < min_sq; });
    if (!crowded) voxel.push_back(p);
  }
}

void VoxelMap::remove_far(const Vec3& sensor_W) {
  const double max_sq = config_.max_distance_m * config_.max_distance_m;
  for (auto it = voxels_.begin(); it != voxels_.end();) {
    const Vec3 centre = (it->first.cast<double>() + Vec3::Constant(0.5)) * config_.voxel_size_m;
    it = (centre - sensor_W).squaredNorm() > max_sq ? voxels_.erase(it) : std::next(it);
  }
}

std::vector<Vec3> VoxelMap::nearest(const Vec3& query_W, int k, double radius_m) const {
  const double radius = std::min(radius_m, config_.voxel_size_m);
  // The best k so far, nearest first. Candidates arrive in a fixed voxel and point order and only a strictly
  // nearer one displaces another, so ties resolve by that order: the result is deterministic.
  std::vector<std::pair<double, const Vec3*>> best;
  best.reserve(static_cast<std::size_t>(std::max(k, 0)) + 1);
  double worst_sq = radius * radius;
  // A ball of radius <= voxel size touches at most 2 voxels per axis.
  const Eigen::Vector3i lo = key_of(query_W - Vec3::Constant(radius));
  const Eigen::Vector3i hi = key_of(query_W + Vec3::Constant(radius));
  for (int x = lo.x(); x <= hi.x(); ++x) {
    for (int y = lo.y(); y <= hi.y(); ++y) {
      for (int z = lo.z(); z <= hi.z(); ++z) {
        const auto it = voxels_.find(Eigen::Vector3i(x, y, z));
        if (it == voxels_.end()) continue;
        for (const Vec3& p : it->second) {
          const double d_sq = (p - query_W).squaredNorm();
          if (d_sq > worst_sq || (d_sq == worst_sq && static_cast<int>(best.size()) == k)) continue;
          auto at = std::upper_bound(best.begin(), best.end(), d_sq,
                                     [](double d, const std::pair<double, const Vec3*>& b) { return d < b.first; });
          best.insert(at, {d_sq, &p});
          if (static_cast<int>(best.size()) > k) best.pop_back();
          if (static_cast<int>(best.size()) == k) worst_sq = best.back().first;
        }
      }
    }
  }
  std::vector<Vec3> result;
  result.reserve(best.size());
  for (const auto& entry : best) result.push_back(*entry.second);
  return result;
}

std::size_t VoxelMap::num_points() const {
  std::size_t n = 0;
  for (const auto& entry : voxels_) n += entry.second.size();
  return n;
}

std::vector<Vec3> VoxelMap::points() const {
  std::vector<Eigen::Vector3i> keys;
  keys.reserve(voxels_.size());
  for (const auto& entry : voxels_) keys.push_back(entry.first);
  std::sort(keys.begin(), keys.end(), key_less);
  std::vector<Vec3> all;
  for (const Eigen::Vector3i& key : keys) {
    const std::vector<Vec3>& voxel = voxels_.at(key);
    all.insert(all.end(), voxel.begin(), voxel.end());
  }
  return all;
}

std::vector<std::size_t> voxel_downsample_indices(const std::vector<Vec3>& points, double leaf_m) {
  tsl::robin_set<Eigen::Vector3i, VoxelKeyHash> seen;
  std::vector<std::size_t> kept;
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (seen.insert(floor_key(points[i], leaf_m)).second) kept.push_back(i);
  }
  return kept;
}

std::vector<Vec3> voxel_downsample(const std::vector<Vec3>& points, double leaf_m) {
  std::vector<Vec3> kept;
  for (const std::size_t i : voxel_downsample_indices(points, leaf_m)) kept.push_back(points[i]);
  return kept;
}

}  // namespace vilslam::lidar
