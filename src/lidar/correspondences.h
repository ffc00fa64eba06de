#pragma once
// Data association of LOAM mapping (Zhang & Singh 2014, Sec. VI): a feature point is matched to the line
// (edge) or plane (surface) fitted to its nearest map points, when the fit is line-like or planar.
#include <optional>
#include <vector>

#include "lidar/residuals.h"
#include "lidar/voxel_map.h"

namespace vilslam::lidar {

struct AssociationConfig {
  int num_neighbors = 5;
  double max_neighbor_distance_m = 1.0;
  double min_line_eigen_ratio = 3.0;          // largest / second eigenvalue of the neighbours' scatter
  double max_plane_point_distance_m = 0.2;    // every neighbour within this of the fitted plane
  // Second / largest eigenvalue of the neighbours' scatter a plane needs: neighbours along one ring (a line
  // with range noise across it) leave the plane's tilt about that line to the noise. Set by the loop ICP only
  // (LoopClosureConfig::icp_min_plane_spread_ratio); LiDAR mapping keeps 0.
  double min_plane_spread_ratio = 0.0;
  // The plane through the nearest neighbour instead of the neighbours' centroid (normal from all of them). On a
  // curved surface (a tunnel's arch) sparse neighbours spread along a ring bulge away from their chord, so the
  // centroid's plane lies inside the surface and every query on it misses to the same side; two sweeps from one
  // pose then come out tilted against each other (docs/loop.md, "Plane fits of single key scans"). Set by the loop
  // ICP only (LoopClosureConfig::icp_plane_through_nearest); LiDAR mapping keeps the centroid.
  bool plane_through_nearest = false;
  // Normal compatibility (Rusinkiewicz and Levoy 2001, "Efficient variants of the ICP algorithm"): a surface
  // point whose own normal is known is matched only to a plane within this angle of it; 0 = no test. Inside a
  // corridor, neighbours that straddle the concave edge between a wall and the ceiling (or floor) fit a plane
  // cutting the corner, nearer the sensor than either surface; the ceiling points matched to such planes pull the
  // sensor down every sweep (docs/lidar.md, "Corner planes").
  double max_normal_angle_deg = 0.0;
};

struct Line {
  Vec3 point = Vec3::Zero();
  Vec3 direction = Vec3::UnitX();
};

struct Plane {
  Vec3 normal = Vec3::UnitZ();
  double offset_m = 0.0;
};

// Principal axis of the points when its eigenvalue dominates the second one by min_eigen_ratio.
std::optional<Line> fit_line(const std::vector<Vec3>& points, double min_eigen_ratio);
// Least-squares plane (smallest scatter eigenvector) when every point lies within max_distance_m of it.
std::optional<Plane> fit_plane(const std::vector<Vec3>& points, double max_distance_m, double min_spread_ratio);

// Correspondence of feature p_L (seen at p_W = T_W_L p_L) with the map, or nothing when the neighbours
// are too few, too far, or not line-like / not planar.
std::optional<EdgeCorrespondence> associate_edge(const Vec3& p_L, const Vec3& p_W, const VoxelMap& edge_map,
                                                 const AssociationConfig& config);
// normal_W: the point's own unit normal in the world frame, zero when unknown (then no normal test).
std::optional<PlaneCorrespondence> associate_plane(const Vec3& p_L, const Vec3& p_W, const VoxelMap& surface_map,
                                                   const AssociationConfig& config, const Vec3& normal_W = Vec3::Zero());

}  // namespace vilslam::lidar
