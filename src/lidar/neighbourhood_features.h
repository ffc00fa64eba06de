#pragma once
// Feature extraction for scans without ring structure (non-repetitive Livox-style sensors, or any cloud):
// each point's k nearest neighbours in the scan give its local scatter (principal component analysis).
// A thin scatter spread in two directions is a surface point; a scatter thick beyond what range noise
// explains (a crease or corner of the scene) is an edge point. Features are spread over angular cells.
#include "common/types.h"

namespace vilslam::lidar {

struct FeatureScan;

struct NeighbourhoodFeatureConfig {
  int num_neighbours = 16;           // k of the k-nearest-neighbour scatter (the point itself included)
  // Every candidate_stride-th point in scan order is a candidate (its neighbours come from all points): the
  // cells keep a few thousand features of a 20,000-point sweep, so a third of the points is plenty.
  int candidate_stride = 3;
  double max_radius_per_range = 0.1; // a scatter whose k-th neighbour is farther than this x range is skipped
  // Thickness = sqrt of the smallest scatter eigenvalue, against the sensor's range noise sigma
  // (FeatureConfig::range_noise_sigma_m): a surface is thinner than surface_max_noise_sigmas sigmas and
  // spread at least min_surface_spread_ratio x its thickness along its second axis; an edge is thicker
  // than edge_min_noise_sigmas sigmas and its smallest eigenvalue is at least edge_min_curvature of the sum.
  double surface_max_noise_sigmas = 1.5;
  double min_surface_spread_ratio = 3.0;
  double edge_min_noise_sigmas = 1.6;
  double edge_min_curvature = 0.05;
  int azimuth_cells = 36;            // features are spread over azimuth x elevation cells of the sensor
  int elevation_cells = 4;
  int max_edges_per_cell = 6;
  int max_surfaces_per_cell = 16;
};

// The features of a scan from its points' neighbourhoods (ring fields ignored); points outside
// [min_range_m, max_range_m] are dropped. range_noise_sigma_m: the sensor's range noise.
FeatureScan extract_neighbourhood_features(const LidarScan& scan, const NeighbourhoodFeatureConfig& config,
                                           double range_noise_sigma_m, double min_range_m, double max_range_m);

}  // namespace vilslam::lidar
