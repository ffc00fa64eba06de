#pragma once
// Post processing of the paper: "we stitch the dewarped LiDAR scans with the best estimated LiDAR poses
// to have the dense mapping results". Every sweep the poses cover is dewarped to its end with the poses
// interpolated over the sweep, moved into W by the pose at its end and averaged into the voxel map.
#include <cstddef>
#include <functional>
#include <limits>
#include <string>

#include "common/types.h"
#include "lidar/mixed_pixels.h"
#include "map/dense_map.h"

namespace vilslam::map {

struct MapBuilderConfig {
  double voxel_size_m = 0.01;
  double min_range_m = 0.5;     // returns closer to the sensor than this are dropped (rig, operator)
  double max_range_m = 50.0;    // and farther ones (pose errors grow with range)
  double max_pose_gap_s = 0.25; // a sweep needs poses no farther apart than this over its whole span
  bool dewarp = true;           // false: every point takes the sweep-end pose (for comparison)
  // A spinning head's sweeps without point times take azimuth times (lidar/azimuth_times.h); false: each is one
  // instant, as the run found them deskewed already (its lidar_sensor.txt says "lidar_azimuth_times: no").
  bool azimuth_times = true;
  // Mixed pixels (lidar/mixed_pixels.h) lie on no surface; sweeps with rings drop them unless this is false.
  bool drop_mixed_pixels = true;
  lidar::MixedPixelConfig mixed_pixels;
  // Optional continuous trajectory (e.g. the odometry lidar.tum) for the motion within each sweep; the poses
  // then only place each sweep's end. Poses published with loop corrections (lidar_global.tum) jump where a
  // correction arrived, and dewarping across that jump would smear the sweep over it.
  Trajectory motion;
  // Time window: only sweeps whose end (IMU clock, the time of their pose in lidar.tum) lies in
  // [window_start_ns, window_end_ns); e.g. the sweeps after a revisit, to compare their map with the rest.
  TimeNs window_start_ns = std::numeric_limits<TimeNs>::min();
  TimeNs window_end_ns = std::numeric_limits<TimeNs>::max();
};

struct MapBuildStats {
  std::size_t sweeps_used = 0;
  std::size_t sweeps_skipped = 0;     // not covered by the poses
  std::size_t sweeps_outside_window = 0;  // covered by the poses, but not ending in the time window
  std::size_t points_inserted = 0;
  std::size_t points_out_of_range = 0;
  std::size_t points_mixed = 0;       // dropped as mixed pixels
};

struct MapBuildResult {
  DenseMap map;
  MapBuildStats stats;
};

// T_W_L: LiDAR poses sorted by strictly increasing time, in the IMU clock (as `vilslam run` writes
// lidar.tum: one per sweep end), or denser. Sweep times are moved to the IMU clock with the
// calibration's lidar_time_offset_ns. Throws InputError naming the dataset when it is missing, has no
// LiDAR, or no sweep in the window is covered by the poses; std::invalid_argument on a bad config (an empty
// window too) or bad poses.
// progress (optional) receives the share of the dataset's sweeps handled so far.
MapBuildResult build_dense_map(const std::string& dataset_path, const Trajectory& T_W_L, const MapBuilderConfig& config,
                               const std::function<void(double)>& progress = {});

}  // namespace vilslam::map
