#include "lidar/neighbourhood_features.h"

#include <tbb/parallel_for.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

#include "common/point_index.h"
#include "lidar/features.h"

namespace vilslam::lidar {

namespace {

enum class Kind : std::uint8_t { kNone, kEdge, kSurface };

// What a point's neighbourhood says of it.
struct Local {
  Kind kind = Kind::kNone;
  float score = 0;          // edges: curvature (higher first); surfaces: thickness in metres (lower first)
  float radius_m = 0;       // distance to the k-th neighbour
  int cell = -1;
  Eigen::Vector3f normal = Eigen::Vector3f::Zero();  // surfaces: the scatter's smallest axis
};

int angular_cell(const Eigen::Vector3f& p, const NeighbourhoodFeatureConfig& config) {
  const double azimuth = std::atan2(p.y(), p.x()) + M_PI;                         // [0, 2 pi]
  const double elevation = std::atan2(p.z(), std::hypot(p.x(), p.y())) + M_PI_2;  // [0, pi]
  const int a = std::min(config.azimuth_cells - 1, static_cast<int>(azimuth / (2 * M_PI) * config.azimuth_cells));
  const int e = std::min(config.elevation_cells - 1, static_cast<int>(elevation / M_PI * config.elevation_cells));
  return e * config.azimuth_cells + a;
}

// The scatter of the k nearest neighbours: eigenvalues ascending (lambda0 <= lambda1 <= lambda2).
Local classify(const PointIndex& index, std::size_t i, const NeighbourhoodFeatureConfig& config, double sigma_m) {
  Local local;
  const Eigen::Vector3f& p = index.points()[i];
  const auto neighbours = index.nearest_k(p, static_cast<std::size_t>(config.num_neighbours));
  if (static_cast<int>(neighbours.size()) < config.num_neighbours) return local;
  local.radius_m = std::sqrt(neighbours.back().dist_sq);
  if (local.radius_m > config.max_radius_per_range * p.norm()) return local;  // sparse: across a gap
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const auto& n : neighbours) mean += index.points()[n.index].cast<double>();
  mean /= static_cast<double>(neighbours.size());
  Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
  for (const auto& n : neighbours) {
    const Eigen::Vector3d d = index.points()[n.index].cast<double>() - mean;
    scatter += d * d.transpose();
  }
  scatter /= static_cast<double>(neighbours.size());
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen;
  eigen.computeDirect(scatter);
  const Eigen::Vector3d lambda = eigen.eigenvalues().cwiseMax(0.0);
  const double thickness_m = std::sqrt(lambda(0));
  const double curvature = lambda(0) / std::max(lambda.sum(), 1e-12);
  if (thickness_m < config.surface_max_noise_sigmas * sigma_m &&
      std::sqrt(lambda(1)) > config.min_surface_spread_ratio * std::max(thickness_m, 1e-3)) {
    local.kind = Kind::kSurface;
    local.score = static_cast<float>(thickness_m);
    local.normal = eigen.eigenvectors().col(0).normalized().cast<float>();
  } else if (thickness_m > config.edge_min_noise_sigmas * sigma_m && curvature > config.edge_min_curvature) {
    local.kind = Kind::kEdge;
    local.score = static_cast<float>(curvature);
  }
  return local;
}

// Takes up to max_per_cell candidates of one kind per cell, best first; a taken point keeps the others
// within its neighbourhood radius out (as LOAM's neighbour suppression along a ring).
std::vector<std::size_t> select(const std::vector<Local>& locals, const std::vector<Eigen::Vector3f>& points, Kind kind,
                                int max_per_cell, int num_cells) {
  std::vector<std::size_t> candidates;
  for (std::size_t i = 0; i < locals.size(); ++i) {
    if (locals[i].kind == kind) candidates.push_back(i);
  }
  const bool higher_first = kind == Kind::kEdge;
  std::sort(candidates.begin(), candidates.end(), [&](std::size_t a, std::size_t b) {
    if (locals[a].score != locals[b].score) return higher_first == (locals[a].score > locals[b].score);
    return a < b;
  });
  std::vector<std::vector<std::size_t>> taken(static_cast<std::size_t>(num_cells));
  std::vector<std::size_t> out;
  for (const std::size_t i : candidates) {
    std::vector<std::size_t>& cell = taken[static_cast<std::size_t>(locals[i].cell)];
    if (static_cast<int>(cell.size()) >= max_per_cell) continue;
    const bool suppressed = std::any_of(cell.begin(), cell.end(), [&](std::size_t j) {
      return (points[i] - points[j]).norm() < locals[j].radius_m;
    });
    if (suppressed) continue;
    cell.push_back(i);
    out.push_back(i);
  }
  std::sort(out.begin(), out.end());  // scan order, independent of the ranking's ties
  return out;
}

}  // namespace

FeatureScan extract_neighbourhood_features(const LidarScan& scan, const NeighbourhoodFeatureConfig& config,
                                           double range_noise_sigma_m, double min_range_m, double max_range_m) {
  FeatureScan features;
  features.t_ns = scan.t_ns;
  std::vector<Eigen::Vector3f> points;
  std::vector<float> t_offset_s;
  for (const LidarPoint& q : scan.points) {
    const Eigen::Vector3f p(q.x, q.y, q.z);
    const float range = p.norm();
    if (!(range >= min_range_m && range <= max_range_m)) continue;
    points.push_back(p);
    t_offset_s.push_back(q.t_offset_s);
  }
  if (static_cast<int>(points.size()) < config.num_neighbours) return features;
  const PointIndex index(points);
  std::vector<Local> locals(points.size());
  const std::size_t stride = static_cast<std::size_t>(config.candidate_stride);
  tbb::parallel_for(std::size_t(0), (points.size() + stride - 1) / stride, [&](std::size_t c) {
    const std::size_t i = c * stride;
    locals[i] = classify(index, i, config, range_noise_sigma_m);
    locals[i].cell = angular_cell(index.points()[i], config);
  });
  const int cells = config.azimuth_cells * config.elevation_cells;
  const auto feature = [&](std::size_t i) {
    return FeaturePoint{index.points()[i].cast<double>(), t_offset_s[i], locals[i].score, locals[i].normal.cast<double>()};
  };
  for (const std::size_t i : select(locals, index.points(), Kind::kEdge, config.max_edges_per_cell, cells)) {
    features.edges.push_back(feature(i));
  }
  for (const std::size_t i : select(locals, index.points(), Kind::kSurface, config.max_surfaces_per_cell, cells)) {
    features.surfaces.push_back(feature(i));
  }
  return features;
}

}  // namespace vilslam::lidar
