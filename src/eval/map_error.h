#pragma once
// Map registration error (MRE): the map cloud is aligned rigidly to the reference model by ICP,
// then each map point's error is its distance to the nearest model point.
//
// Where ICP starts (docs/evaluation.md): the identity when the map is already near the model's frame;
// for a map in the estimator's own world (the VIO's initial gravity-aligned frame) the first-pose rule,
// T_model_map = T_gt(t0) T_est(t0)^-1 at the first estimated pose t0 (no alignment by the whole ground
// truth: what the rest of the trajectory drifted stays in the map for ICP and the MRE to see).
#include <cstddef>
#include <optional>
#include <vector>

#include "common/types.h"
#include "eval/icp.h"
#include "io/cloud_io.h"

namespace vilslam::eval {

// Where ICP starts, and by which rule.
struct InitialAlignment {
  SE3 T_model_map;                        // p_model = T_model_map * p_map
  std::optional<TimeNs> first_pose_t_ns;  // t0 of the first-pose rule; nullopt: the identity
};

struct MapErrorConfig {
  bool align = true;  // false: errors of the map moved by `initial` alone, without ICP
  IcpConfig icp;
  // ICP aligns every k-th map point, k chosen so that at most this many take part (0: all). A 1 cm
  // dense map holds tens of millions of points, far more than a rigid alignment needs; the errors are
  // still computed for every point.
  std::size_t max_icp_points = 200000;
  InitialAlignment initial;  // where ICP starts (first_pose_alignment, or the identity)
};

struct MapError {
  std::vector<float> per_point_m;  // one per map point, in map order
  double mean_m = 0, median_m = 0, p95_m = 0;
  IcpResult icp;                   // the initial T_model_map and 0 iterations when not aligned
};

// Throws std::invalid_argument on an empty map or model.
MapError compute_map_error(const PointCloud& map, const PointCloud& model, const MapErrorConfig& config);

// The same, but the alignment is found on align_map, a cloud in the map's frame (e.g. the whole map of
// which `map` is a part), and the errors are those of `map` under it: a part of a map measured in the
// whole map's alignment shows whether it lies on the same surfaces as the rest.
MapError compute_map_error(const PointCloud& map, const PointCloud& align_map, const PointCloud& model,
                           const MapErrorConfig& config);

// The first-pose rule: T_model_map = T_gt(t0) T_est(t0)^-1, t0 the time of est's first pose, the ground
// truth (in the model's frame, same body frame as est) interpolated at t0. Throws std::invalid_argument
// when est is empty, the ground truth has fewer than 2 poses, or t0 lies outside its time span.
InitialAlignment first_pose_alignment(const Trajectory& est, const Trajectory& gt);

}  // namespace vilslam::eval
