#pragma once
// JSON documents of the evaluation results (the --json outputs of `vilslam eval` and `vilslam eval-map`).
#include <string>

#include "eval/map_error.h"
#include "eval/trajectory_eval.h"

namespace vilslam::eval {

// {"ape": {rmse, mean, median, std, min, max}, "ape_rot_deg": {...}, "rpe": {...}, "rpe_rot_deg": {...},
//  "rpe_delta": {value, unit}, "kitti": {t_err_percent, r_err_deg_per_m, segments}, "fde_percent",
//  "fde_start_aligned_percent", "path_length_m", "matched_poses", "alignment": {mode, scale, T (4x4 rows)}}
std::string trajectory_report_json(const TrajectoryEvalReport& report, const TrajectoryEvalConfig& config);

// {"points", "mean_m", "median_m", "p95_m", "aligned", "initial_alignment": {rule ("first_pose" or
//  "identity"), first_pose_t_ns (null for the identity), T_model_map (4x4 rows)}, "icp": {mode, iterations,
//  converged, inliers, rmse_m, max_correspondence_m, T_model_map (4x4 rows, the final alignment)}}
std::string map_error_json(const MapError& error, const MapErrorConfig& config);

}  // namespace vilslam::eval
