#include "lidar/sensor_adaptation.h"

namespace vilslam::lidar {
namespace {

// field = value, unless the given config moved it off its built-in default (the user's choice wins).
template <typename T>
void unless_set(T& field, const T& built_in, const T& value) {
  if (field == built_in) field = value;
}

}  // namespace

LidarMapperConfig adapt_to_sensor(const LidarMapperConfig& given, const SensorTraits& traits) {
  LidarMapperConfig c = given;
  if (!traits.read() || traits.spinning()) return c;
  const LidarMapperConfig d;
  // No rings: features from point neighbourhoods, every point a candidate, surfaces only (edges add about 2 mm a
  // sweep along a corridor's creases), three times the surfaces per cell (docs/lidar.md, "More neighbourhood
  // features", "Denser Mid-360 scans and the per-match degeneracy test").
  NeighbourhoodFeatureConfig& n = c.lidar.features.neighbourhood;
  const NeighbourhoodFeatureConfig& dn = d.lidar.features.neighbourhood;
  unless_set(c.lidar.features.method, d.lidar.features.method, FeatureMethod::kNeighbourhood);
  unless_set(n.candidate_stride, dn.candidate_stride, 1);
  unless_set(n.max_edges_per_cell, dn.max_edges_per_cell, 0);
  unless_set(n.max_surfaces_per_cell, dn.max_surfaces_per_cell, 48);
  // Denser scan surfaces, planes only within 10 deg of a point's own normal and within 5 cm of their points (not
  // across a wall-ceiling crease), a degeneracy test scaled to the denser scan.
  RegistrationConfig& r = c.lidar.registration;
  const RegistrationConfig& dr = d.lidar.registration;
  unless_set(r.source_surface_leaf_m, dr.source_surface_leaf_m, 0.1);
  unless_set(r.association.max_normal_angle_deg, dr.association.max_normal_angle_deg, 10.0);
  unless_set(r.association.max_plane_point_distance_m, dr.association.max_plane_point_distance_m, 0.05);
  unless_set(r.degenerate_min_eigenvalue_per_match, dr.degenerate_min_eigenvalue_per_match, 0.01);
  // No tilt prior: the VIO's tilt reaches L through the calibrated mount, and with a field of view above the
  // horizon a mount a fraction of a degree off wins over a ceiling seen alone.
  unless_set(r.tilt_prior_sigma_rad, dr.tilt_prior_sigma_rad, 0.0);
  return c;
}

}  // namespace vilslam::lidar
