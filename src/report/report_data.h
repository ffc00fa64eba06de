#pragma once
// Everything a report shows, computed from a run folder and the optional ground truth, map and model;
// report_json.h writes it into the page.
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "common/types.h"
#include "report/histogram.h"
#include "report/map_view.h"
#include "report/run_dir.h"
#include "report/trajectory_errors.h"

namespace vilslam::report {

struct ReportOptions {
  std::string run_dir;
  std::string gt_path;     // "" = none: a dataset folder or a TUM file (taken as the ground truth of every body frame)
  std::string map_path;    // "" = none: a map cloud of `vilslam map` (.ply, .pcd)
  std::string model_path;  // "" = none: a reference model; colours the map by MRE (needs map_path)
  std::size_t max_path_points = 3000;  // per drawn trajectory
  std::size_t max_map_points = 200000;
  std::size_t histogram_bins = 40;
};

// One estimated trajectory as drawn: in the ground truth's world when there is one (aligned), else its own.
struct DrawnTrajectory {
  std::string name;  // "VIO", "LiDAR odometry", "LiDAR loop-closed"
  std::string file;  // in the run folder
  Trajectory T_W_B;  // drawn poses (the whole trajectory)
  std::optional<TrajectoryErrors> errors;  // against the ground truth
};

struct TimingHistogram {
  std::string series;
  Histogram ms;
};

struct ReportData {
  RunDir run;
  std::string gt_path;
  std::optional<Trajectory> gt_T_W_B;  // the ground truth drawn: of the first estimate's body frame
  std::string gt_frame;                // "IMU" | "LiDAR"
  std::vector<DrawnTrajectory> trajectories;
  std::optional<std::size_t> events_on;  // index of the trajectory degenerate sweeps and loops are drawn on
  std::vector<TimingHistogram> histograms;
  std::string map_path, model_path;
  std::optional<MapView> map;
  Trajectory map_path_T_W_L;  // the LiDAR poses in the map's world (the map was built with them)
  std::vector<std::string> notes;  // what is left out, and why
  TimeNs t0_ns = 0;  // times in the page count from here (the first estimated pose)
};

// Throws InputError naming the file on a missing or malformed input.
ReportData build_report_data(const ReportOptions& options);

}  // namespace vilslam::report
