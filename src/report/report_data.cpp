#include "report/report_data.h"

#include <stdexcept>

#include "common/error.h"
#include "io/cloud_io.h"
#include "io/dataset_groundtruth.h"

namespace vilslam::report {
namespace {

// VIO poses are compared by position and yaw (its unobservable directions), LiDAR poses by SE(3), as in
// the demo's `vilslam eval` calls (docs/evaluation.md).
struct TrajectorySpec {
  const char* name;
  const char* file;
  const std::optional<Trajectory>& T_W_B;
  GroundTruthFrame frame;
  eval::AlignMode align;
};

void add_trajectories(const ReportOptions& options, ReportData& data) {
  const RunDir& run = data.run;
  const std::vector<TrajectorySpec> specs = {
      {"VIO", "vio_camera.tum", run.vio_T_W_I, GroundTruthFrame::kImu, eval::AlignMode::kPosYaw},
      {"LiDAR odometry", "lidar.tum", run.lidar_odometry_T_W_L, GroundTruthFrame::kLidar, eval::AlignMode::kSe3},
      {"LiDAR loop-closed", "lidar_final.tum", run.lidar_final_T_W_L, GroundTruthFrame::kLidar, eval::AlignMode::kSe3}};
  for (const TrajectorySpec& spec : specs) {
    if (!spec.T_W_B || spec.T_W_B->empty()) continue;
    DrawnTrajectory drawn{spec.name, spec.file, *spec.T_W_B, std::nullopt};
    if (!options.gt_path.empty()) {
      const Trajectory gt = read_groundtruth(options.gt_path, spec.frame);
      if (!data.gt_T_W_B) {
        data.gt_T_W_B = gt;
        data.gt_frame = spec.frame == GroundTruthFrame::kImu ? "IMU" : "LiDAR";
      }
      try {
        drawn.errors = trajectory_errors(*spec.T_W_B, gt, spec.align);
        drawn.T_W_B = drawn.errors->est_in_gt_world;
      } catch (const std::invalid_argument& e) {  // drawn in its own world it would mislead next to the others
        data.notes.push_back(std::string(spec.file) + ": left out, not aligned with the ground truth (" + e.what() + ")");
        continue;
      }
    }
    data.trajectories.push_back(std::move(drawn));
  }
  if (data.trajectories.empty())
    throw InputError(run.path, "no trajectory to draw (empty files, or none aligned with the ground truth " +
                                   options.gt_path + ")");
  data.t0_ns = data.trajectories.front().T_W_B.front().t_ns;
  if (options.gt_path.empty())
    data.notes.push_back("no ground truth given (--gt): paths are drawn in their own worlds, without errors");
  for (std::size_t i = 0; i < data.trajectories.size(); ++i) {
    if (data.trajectories[i].file != "vio_camera.tum") data.events_on = i;
  }
}

void add_histograms(const ReportOptions& options, ReportData& data) {
  for (const TimingSamples& s : data.run.timings.samples)
    data.histograms.push_back({s.series, histogram_from_zero(s.samples_ms, options.histogram_bins)});
  if (data.run.timings.samples.empty())
    data.notes.push_back("no timing_samples.csv in the run folder (a run made before it was written): timing summaries only");
}

// The LiDAR poses the map was built with: the loop-closed ones when the run has them (docs/map.md).
const Trajectory& map_poses(const RunDir& run) {
  if (run.lidar_final_T_W_L) return *run.lidar_final_T_W_L;
  if (run.lidar_odometry_T_W_L) return *run.lidar_odometry_T_W_L;
  throw InputError(run.path, "a map needs LiDAR poses (lidar.tum)");
}

void add_map(const ReportOptions& options, ReportData& data) {
  if (options.map_path.empty()) {
    data.notes.push_back("no map given (--map): no 3D view");
    return;
  }
  data.map_path = options.map_path;
  data.map_path_T_W_L = map_poses(data.run);
  const PointCloud map = read_cloud(options.map_path);
  if (map.points.empty()) throw InputError(options.map_path, "cloud has no points");
  if (options.model_path.empty()) {
    data.map = map_view(map, options.max_map_points);
    data.notes.push_back("no reference model given (--model): the map is coloured by height");
    return;
  }
  data.model_path = options.model_path;
  const PointCloud model = read_cloud(options.model_path);
  if (model.points.empty()) throw InputError(options.model_path, "cloud has no points");
  eval::MapErrorConfig config;
  if (!options.gt_path.empty()) {
    try {
      config.initial = eval::first_pose_alignment(data.map_path_T_W_L,
                                                  read_groundtruth(options.gt_path, GroundTruthFrame::kLidar));
    } catch (const std::invalid_argument& e) {
      throw InputError(options.gt_path, std::string("cannot align the map by the first pose: ") + e.what());
    }
  }
  try {
    data.map = map_view_with_error(map, model, config, options.max_map_points);
  } catch (const std::invalid_argument& e) {
    throw InputError(options.map_path, std::string("cannot register against ") + options.model_path + ": " + e.what());
  }
}

}  // namespace

ReportData build_report_data(const ReportOptions& options) {
  if (!options.model_path.empty() && options.map_path.empty())
    throw std::invalid_argument("--model needs --map (the map to measure against the model)");
  ReportData data;
  data.run = read_run_dir(options.run_dir);
  data.gt_path = options.gt_path;
  add_trajectories(options, data);
  if (!data.run.loops) data.notes.push_back("no loops.csv in the run folder (loop closure did not run): no loops drawn");
  if (!data.run.degeneracy) data.notes.push_back("no degeneracy.csv in the run folder (no LiDAR): no degenerate sweeps drawn");
  add_histograms(options, data);
  add_map(options, data);
  return data;
}

}  // namespace vilslam::report
