#pragma once
// The paper's Table I on simulated presets: per preset the final drift of the VIO, of the VIL LiDAR
// odometry, of LiDAR-only mapping and of the loop-closed VIL trajectory, their ATE against ground truth, the
// degenerate sweeps, the loops found and their errors, the MRE of the dense maps made with those poses,
// next to the paper's values; rendered as Markdown (docs/odometry.md).
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "common/types.h"
#include "eval/alignment.h"
#include "eval/loop_eval.h"

namespace vilslam::eval {

// One estimated trajectory of a run, or why the run produced none.
struct RunTrajectory {
  Trajectory poses;
  std::string failure;  // non-empty: the run threw (its message)
};

// Loop closure of the VIL run: how many candidates it examined and the loops it accepted (T_Lu_Lv with
// from = the old key scan u, to = the current one v, as in loops.csv).
struct LoopClosureInputs {
  std::size_t candidates_examined = 0;
  std::vector<LoopToEvaluate> accepted;
};

// Everything one row needs. Ground truth and estimates of the LiDAR runs are in the LiDAR frame (T_W_L).
struct OdometryInputs {
  std::string preset;
  std::string source;        // where the simulation came from, for the table
  Trajectory gt_T_W_I;       // ground truth of the IMU body
  Trajectory gt_T_W_L;       // ground truth of the LiDAR (T_W_I T_I_L)
  RunTrajectory vio;         // camera-rate VIO states T_W_I
  RunTrajectory vil;         // VIL LiDAR odometry T_W_L (lidar.tum: the mapper's motion, no loop correction)
  RunTrajectory vil_final;   // VIL LiDAR poses T_W_L after loop closure (lidar_final.tum)
  std::optional<LoopClosureInputs> loops;  // nullopt: the VIL run failed
  RunTrajectory lidar_only;  // LiDAR-only mapping poses T_W_L
  std::size_t vil_degenerate = 0, vil_sweeps = 0;
  std::size_t lidar_only_degenerate = 0, lidar_only_sweeps = 0;
};

// When a run counts as lost (besides throwing, producing < 2 poses or a non-finite pose).
struct LostCriteria {
  double min_coverage = 0.5;       // the estimate spans at least this fraction of the ground truth's time span
  double max_error_fraction = 0.1; // after ATE alignment no pose is farther from ground truth than this
  double max_error_floor_m = 1.0;  //   fraction of the path length, or this many metres if more
};

// A route closes when its ground truth ends within this distance of its start.
constexpr double kClosedRouteGapM = 0.01;

struct DriftResult {
  bool lost = false;
  std::string lost_reason;
  std::size_t poses = 0;
  double fde_percent = 0;     // see OdometryRow::closed
  double drift_m = 0;
  double path_length_m = 0;   // the length the FDE is relative to
  double ate_rmse_m = 0;      // APE translation RMSE after the alignment `align`
  double ape_max_m = 0;       //   and its largest APE (the lost rule)
  double ate_se3_rmse_m = 0;  // APE translation RMSE after an SE(3) alignment (NaN: positions on a line)
  AlignMode align = AlignMode::kNone;
};

struct LoopClosureResult {
  std::size_t candidates_examined = 0;
  LoopEvaluation accepted;  // one entry per accepted loop; its false_loops exceed 0.3 m or 3 degrees
};

// MRE of the dense map built with one trajectory's LiDAR poses, aligned to the reference model by the
// first-pose rule then ICP (eval/map_error.h), as `vilslam map` then `vilslam eval-map --first-pose` do.
struct MapRegistration {
  std::string failure;  // non-empty: no MRE, and why (the run is lost, the map or ICP failed)
  std::size_t points = 0;
  double mean_m = 0, median_m = 0, p95_m = 0;
  bool icp_converged = false;
  double wall_s = 0;    // building the map and measuring it
};

// The dense maps of one preset, all with voxels of voxel_m.
struct MapErrors {
  double voxel_m = 0;
  MapRegistration vil;         // lidar.tum of the vil run (odometry)
  MapRegistration vil_final;   // lidar_final.tum (loop-corrected)
  MapRegistration lidar_only;  // the paper's LOAM column
  MapRegistration truth;       // ground-truth poses: the floor of range noise, voxels and model spacing
};

struct OdometryRow {
  std::string preset, source;
  double gt_length_m = 0;
  double gt_gap_m = 0;   // ground truth: distance between its last and first position
  bool closed = false;   // gt_gap_m <= kClosedRouteGapM: FDE = |p_last - p_first| of the estimate over its
                         // path length (paper); otherwise the start-aligned drift against ground truth
  DriftResult vio, vil, lidar_only;
  DriftResult vil_final;                   // after loop closure, evaluated like vil
  std::optional<LoopClosureResult> loops;  // nullopt: the VIL run failed
  std::size_t vil_degenerate = 0, vil_sweeps = 0;
  std::size_t lidar_only_degenerate = 0, lidar_only_sweeps = 0;
  std::optional<MapErrors> maps;  // nullopt: not measured (the command measures them after the row)
};

// FDE, ATE and the lost verdict of one estimate against its ground truth (same frame).
DriftResult evaluate_drift(const RunTrajectory& run, const Trajectory& gt, AlignMode align, bool closed,
                           const LostCriteria& criteria = {});

// Throws std::invalid_argument when the ground truth has fewer than 2 poses or does not span a loop's instants.
OdometryRow compute_odometry_row(const OdometryInputs& in, const LostCriteria& criteria = {});

// The paper's Table I (odometry FDE in %, path length in m, MRE in m) for a preset and what its results
// section says of loop closure on it; nullopt for presets it lacks.
struct PaperOdometry {
  std::string test;                   // the paper's name of the test
  double length_m = 0;
  double vil_slam_fde_percent = 0;
  std::optional<double> loam_fde_percent;  // nullopt: LOAM did not finish
  std::optional<double> vil_slam_loop_fde_percent;  // FDE after loop closure, when the text gives one
  std::string loop_remark;            // otherwise what the text says ("" when it says nothing)
  std::optional<double> vil_slam_mre_m, loam_mre_m;  // nullopt: the paper's "x" (no model of that test)
};
std::optional<PaperOdometry> paper_odometry(const std::string& preset);

}  // namespace vilslam::eval
