#pragma once
// LOAM feature extraction (Zhang & Singh 2014, Sec. V-A): per ring, the smoothness of each point over its
// neighbours along the ring picks sharp edge points and flat surface points, spread evenly over sectors.
// A scan without ring structure (a non-repetitive sensor) takes its features from point neighbourhoods
// instead (neighbourhood_features.h).
#include <vector>

#include "common/lie.h"
#include "common/types.h"
#include "lidar/neighbourhood_features.h"
#include "lidar/ring_assignment.h"

namespace vilslam::lidar {

enum class FeatureMethod {
  kAuto,           // rings when the scan has a ring field or its elevations fall on the configured rings
  kRings,          // LOAM along rings (from the ring field, else from elevation)
  kNeighbourhood,  // point neighbourhoods, for scans without rings
};

struct FeatureConfig {
  FeatureMethod method = FeatureMethod::kAuto;
  // With more rings than this the per-sector counts shrink in proportion (a 128-beam sensor takes a quarter
  // per ring), so that a sweep gives no more features than a sensor of this many rings.
  int reference_rings = 32;
  // Ring surface features get normals from their neighbouring rings (ring_normals.h). They cost a few ms a
  // sweep and only the registration's normal test uses them: features_for_registration (lidar_config.h) sets
  // this from it.
  bool ring_normals = false;
  NeighbourhoodFeatureConfig neighbourhood;
  int half_window = 5;              // neighbours on each side along the ring for the smoothness
  int sectors_per_ring = 6;         // each ring is split into this many equal sub-regions
  int max_edges_per_sector = 20;
  int max_surfaces_per_sector = 40;
  double edge_min_smoothness = 0.02;     // LOAM eq. (1), dimensionless: above this a point may be an edge
  // An edge must also stand out of range noise: c > edge_noise_sigmas x (smoothness std of a noisy plane),
  // which is ~ range_noise_sigma_m / range (features.cpp); it rejects noise "edges" on walls within ~4 m.
  // 4 sigmas: below one false edge among the thousands of points of a sweep (two-sided tail 6e-5).
  // 2 cm: the order of the VLP-16 datasheet's "+-3 cm typical" range accuracy (also the simulator's default
  // noise; the value comes from the sensor's data sheet, not from the generator).
  double range_noise_sigma_m = 0.02;
  // On an oblique surface the beam's footprint spreads the range by 0.5 r divergence tan(incidence), which
  // the edge test adds to the range noise (features.cpp). 3 mrad: the VLP-16 data sheet; 0 ignores it.
  double beam_divergence_rad = 0.003;
  double edge_noise_sigmas = 4.0;
  double surface_max_smoothness = 0.005; // below this a point may be a surface point
  double occlusion_jump_ratio = 0.1;     // a range jump above this fraction of the range marks an occlusion
  double max_neighbor_gap_ratio = 0.02;  // both neighbour gaps above this fraction of range: beam ~ surface
};

// A feature point in the LiDAR frame at its own measurement instant.
struct FeaturePoint {
  Vec3 p_L = Vec3::Zero();
  float t_offset_s = 0.0f;  // since the scan's t_ns
  float smoothness = 0.0f;  // LOAM eq. (1); neighbourhood features: curvature (edges), thickness in m (surfaces)
  // Unit normal of a surface feature from its neighbourhood in the sweep (neighbourhood features: its k nearest
  // points; ring features, with FeatureConfig::ring_normals: the neighbouring rings, ring_normals.h); zero for
  // edges, for a surface whose neighbourhood shows no plane, and for features read from a map file.
  Vec3 normal_L = Vec3::Zero();
};

struct FeatureScan {
  TimeNs t_ns = 0;  // the sweep's start time
  std::vector<FeaturePoint> edges;
  std::vector<FeaturePoint> surfaces;
};

// The method `auto` resolves to for this scan: rings when it has a ring field, or when at least 70 % of its
// points lie within a quarter ring spacing of a configured ring elevation (uniform elevations give 50 %).
FeatureMethod resolve_feature_method(const LidarScan& scan, const RingConfig& ring_config, FeatureMethod method);

FeatureScan extract_features(const LidarScan& scan, const RingConfig& ring_config, const FeatureConfig& config);

}  // namespace vilslam::lidar
