#include "lidar/correspondences.h"

#include <Eigen/Eigenvalues>

namespace vilslam::lidar {

namespace {

struct Scatter {
  Vec3 mean = Vec3::Zero();
  Eigen::SelfAdjointEigenSolver<Mat3> eigen;  // eigenvalues ascending
};

Scatter scatter_of(const std::vector<Vec3>& points) {
  Scatter s;
  for (const Vec3& p : points) s.mean += p;
  s.mean /= static_cast<double>(points.size());
  Mat3 covariance = Mat3::Zero();
  for (const Vec3& p : points) covariance += (p - s.mean) * (p - s.mean).transpose();
  s.eigen.computeDirect(covariance / static_cast<double>(points.size()));
  return s;
}

}  // namespace

std::optional<Line> fit_line(const std::vector<Vec3>& points, double min_eigen_ratio) {
  if (points.size() < 2) return std::nullopt;
  const Scatter s = scatter_of(points);
  const Vec3 lambda = s.eigen.eigenvalues();
  if (!(lambda(2) > 0.0) || lambda(2) < min_eigen_ratio * lambda(1)) return std::nullopt;
  return Line{s.mean, s.eigen.eigenvectors().col(2).normalized()};
}

std::optional<Plane> fit_plane(const std::vector<Vec3>& points, double max_distance_m, double min_spread_ratio) {
  if (points.size() < 3) return std::nullopt;
  const Scatter s = scatter_of(points);
  const Vec3 normal = s.eigen.eigenvectors().col(0).normalized();
  // Nearly collinear points leave the normal undetermined.
  const Vec3 lambda = s.eigen.eigenvalues();
  if (!(lambda(1) > 1e-9) || lambda(1) < min_spread_ratio * lambda(2)) return std::nullopt;
  const Plane plane{normal, -normal.dot(s.mean)};
  for (const Vec3& p : points) {
    if (std::abs(plane.normal.dot(p) + plane.offset_m) > max_distance_m) return std::nullopt;
  }
  return plane;
}

std::optional<EdgeCorrespondence> associate_edge(const Vec3& p_L, const Vec3& p_W, const VoxelMap& edge_map,
                                                 const AssociationConfig& config) {
  const std::vector<Vec3> neighbors = edge_map.nearest(p_W, config.num_neighbors, config.max_neighbor_distance_m);
  if (static_cast<int>(neighbors.size()) < config.num_neighbors) return std::nullopt;
  const std::optional<Line> line = fit_line(neighbors, config.min_line_eigen_ratio);
  if (!line) return std::nullopt;
  return EdgeCorrespondence{p_L, line->point, line->direction};
}

std::optional<PlaneCorrespondence> associate_plane(const Vec3& p_L, const Vec3& p_W, const VoxelMap& surface_map,
                                                   const AssociationConfig& config, const Vec3& normal_W) {
  const std::vector<Vec3> neighbors =
      surface_map.nearest(p_W, config.num_neighbors, config.max_neighbor_distance_m);
  if (static_cast<int>(neighbors.size()) < config.num_neighbors) return std::nullopt;
  const std::optional<Plane> plane = fit_plane(neighbors, config.max_plane_point_distance_m, config.min_plane_spread_ratio);
  if (!plane) return std::nullopt;
  if (config.max_normal_angle_deg > 0.0 && !normal_W.isZero() &&
      std::abs(plane->normal.dot(normal_W)) < std::cos(config.max_normal_angle_deg * M_PI / 180.0)) {
    return std::nullopt;
  }
  const double offset_m = config.plane_through_nearest ? -plane->normal.dot(neighbors.front()) : plane->offset_m;
  return PlaneCorrespondence{p_L, plane->normal, offset_m};
}

}  // namespace vilslam::lidar
