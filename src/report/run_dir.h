#pragma once
// The files of a `vilslam run --out DIR` folder that the report draws (docs/pipeline.md lists them all).
// Only timings.json is required; every other file is optional, and a file that is present must be valid.
#include <optional>
#include <string>
#include <vector>

#include "common/types.h"
#include "loop/loop_constraints_io.h"

namespace vilslam::report {

// One row of degeneracy.csv: a mapped sweep.
struct SweepDegeneracy {
  TimeNs t_ns = 0;
  bool degenerate = false;
  double min_eigenvalue = 0;  // smallest eigenvalue of the registration's J^T J
};

// The per-event times of one series of timing_samples.csv ("frontend", "imu_pose_latency", ...).
struct TimingSamples {
  std::string series;
  std::vector<double> samples_ms;
};

// The summary of one series in timings.json.
struct TimingSummaryRow {
  std::string series;
  double frames = 0, median_ms = 0, p95_ms = 0, max_ms = 0;
};

struct RunTimings {
  std::string mode;  // "vio" | "vil" | "lidar-only"
  double data_s = 0, run_wall_s = 0;
  std::optional<double> realtime_speed;      // with --realtime
  std::vector<TimeNs> lidar_lost_t_ns;       // when LiDAR mapping was lost (a reset followed in vil with loop closure)
  std::vector<TimingSummaryRow> summaries;   // every series of timings.json, latencies last
  std::vector<TimingSamples> samples;        // from timing_samples.csv; empty when the file is absent
};

struct RunDir {
  std::string path;
  std::optional<Trajectory> vio_T_W_I;            // vio_camera.tum
  std::optional<Trajectory> lidar_odometry_T_W_L; // lidar.tum
  std::optional<Trajectory> lidar_final_T_W_L;    // lidar_final.tum (loop-corrected)
  std::optional<std::vector<loop::LoopRow>> loops;  // loops.csv
  std::optional<std::vector<SweepDegeneracy>> degeneracy;  // degeneracy.csv
  RunTimings timings;
};

// Throws InputError naming the folder or file: a missing folder, a missing timings.json, a folder without
// any trajectory, or a present file that is unreadable or malformed.
RunDir read_run_dir(const std::string& path);

}  // namespace vilslam::report
