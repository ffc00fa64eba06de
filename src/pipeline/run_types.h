#pragma once
// What a run is configured with and what it produces: shared by the System (pipeline/system.h), which runs the
// modules, and the offline runner (pipeline/offline_runner.h), which feeds it a dataset.
#include <optional>
#include <string>
#include <vector>

#include "common/types.h"
#include "frontend/frontend_config.h"
#include "lidar/lidar_mapper.h"
#include "loop/global_pose_graph.h"
#include "loop/loop_closer.h"
#include "pipeline/loop_closure_module.h"
#include "pipeline/realtime.h"
#include "vio/time_offset.h"
#include "vio/vio.h"
#include "vio/vio_status.h"

namespace vilslam {

enum class RunMode { kVio, kVil, kLidarOnly };

// "vio" | "vil" | "lidar-only"; throws std::invalid_argument otherwise.
RunMode parse_run_mode(const std::string& name);
std::string run_mode_name(RunMode mode);

// The vocabulary shipped in config/ (docs/loop.md).
std::string default_vocabulary_path();
// The file a config's `vocabulary` names: "default" is default_vocabulary_path().
std::string vocabulary_file(const std::string& name);

struct OfflineRunConfig {
  RunMode mode = RunMode::kVio;
  FrontendConfig frontend;
  VioConfig vio;
  lidar::LidarMapperConfig lidar;
  loop::LoopClosureConfig loop;         // vil mode only (it needs key images)
  loop::GlobalPoseGraphConfig graph;
  std::string vocabulary = "default";   // a vocabulary file, or "default": default_vocabulary_path()
  // vil with loop closure: a saved map (loop/map_file.h) to re-localize in (docs/loop.md, "Map reuse"); not
  // part of the run YAML (run --load-map).
  std::string load_map;
  // vil with loop closure: reset the whole state at these times (s from the first event, increasing); each new
  // segment re-localizes in the map of the ones before it (docs/loop.md, "Forced resets"). Not in the YAML
  // (run --reset-at).
  std::vector<double> reset_at_s;
  TimeOffsetConfig time_offset;          // vio and vil: estimate the camera-IMU time offset before the run
  bool threads = true;  // the frontend, the smoother and the LiDAR side each on a thread (same output as without)
  // vil with loop closure: when LiDAR mapping is lost (lidar/mapping_loss.h) the whole state is reset as by
  // reset_at_s, at the first check from then on; offline the checks wait for the modules to catch up, every
  // reset_check_s of data, so that the reset's instant depends on the data only (docs/pipeline.md, "Resets").
  bool reset_on_lidar_lost = true;
  double reset_check_s = 0.5;
  RealtimeConfig realtime;  // speed 0: offline (deterministic); > 0: events on the wall clock (pipeline/realtime.h)
};

// The run resets the whole state when LiDAR mapping is lost (vil with loop closure and reset_on_lidar_lost);
// otherwise LiDAR mapping re-anchors itself (pipeline/lidar_feeder.h).
inline bool resets_on_lidar_lost(const OfflineRunConfig& c) {
  return c.reset_on_lidar_lost && c.mode == RunMode::kVil && c.loop.enabled;
}

// The most messages that waited at once in each module's queue (0 for a module the mode does not run).
struct QueueDepths {
  std::size_t frontend = 0;
  std::size_t smoother = 0;
  std::size_t lidar = 0;
};

// Real-time mode only: each output's latency (wall time from its measurement's instant to its publication) and
// what the overload policy dropped.
struct RealtimeStats {
  double speed = 0.0;
  Trajectory live_imu_poses;  // T_W_I published as each IMU sample arrived (pipeline/live_propagator.h)
  std::vector<double> imu_pose_latency_ms;      // per live IMU-rate pose, from its IMU sample's time
  std::vector<double> camera_state_latency_ms;  // per optimized camera-rate state, from its stereo pair's time
  std::vector<double> lidar_pose_latency_ms;    // per mapped sweep, from the sweep's end
  std::size_t dropped_frames = 0;
  std::size_t dropped_sweeps = 0;
  double max_release_lag_ms = 0.0;  // how late the reader released an event (reading it took longer than its slot)
  QueueDepths max_queue_depth;
  double cpu_s = 0.0;  // CPU time of the whole process (every thread) over the run
};

// A run with resets: one segment, from its start to the next reset.
struct RunSegment {
  TimeNs start_t_ns = 0;    // the reset (the first event for the first segment)
  std::size_t sweeps = 0;   // mapped
  std::size_t key_frames = 0;
  // When it joined the map of the segments before it (or a loaded map), and where its own frame lay there.
  std::optional<TimeNs> relocalized_t_ns;
  SE3 T_map_run;
  std::size_t map_candidates = 0, map_candidates_accepted = 0, map_loops = 0;
};

// An online estimate of the camera-IMU time offset (time_offset.online) and the offset it set for the frames after it.
struct OnlineTimeOffsetUpdate {
  TimeNs t_ns = 0;  // IMU-clock time of the frame whose rotation completed the estimate
  TimeOffsetEstimate estimate;
  // The estimate, its change limited to a quarter of the frame interval so that frame times keep increasing.
  double applied_offset_s = 0;
};

struct OfflineRunResult {
  Trajectory camera_states;  // T_W_I of every optimized stereo-frame state (IMU clock)
  std::vector<VioStatusRecord> vio_status;  // what each of those states went through (vio_status.csv)
  Trajectory imu_poses;      // T_W_I propagated at every IMU sample after initialization
  Trajectory imu_motion;     // T_O_I at the same samples: the same motion without re-anchoring jumps
  std::vector<int> matches_per_frame;
  std::vector<double> frontend_ms;  // per stereo frame
  std::vector<double> smoother_ms;  // per stereo frame (Vio::add_frame)
  std::size_t imu_samples = 0;
  std::vector<lidar::LidarMappingResult> lidar;  // one per mapped sweep
  std::vector<lidar::LidarMappingResult> lidar_rejected;  // the sweeps mapping rejected (lidar/mapping_loss.h)
  std::vector<TimeNs> lidar_lost_t_ns;  // when LiDAR mapping was lost (at most once a segment)
  std::size_t unmapped_scans = 0;  // sweeps no VIO pose covered (vil), or after mapping was lost
  std::string lidar_sensor;  // the LiDAR as the run read it (LidarFeeder::sensor_report; lidar_sensor.txt)
  std::optional<LoopClosureOutput> loop;  // vil: odometry, loop-corrected poses, loop candidates
  std::optional<TimeOffsetEstimate> time_offset;  // when estimated (config.time_offset.enabled) and observable
  std::vector<OnlineTimeOffsetUpdate> time_offset_online;  // config.time_offset.online: every estimate made
  double data_s = 0;      // time span of the events read (the sensors' time)
  double run_wall_s = 0;  // wall time of run_offline (data_s / run_wall_s > 1: faster than real time)
  std::optional<RealtimeStats> realtime;  // when config.realtime.speed > 0
  std::vector<RunSegment> segments;       // with resets (config.reset_at_s): one per segment, else none
};

}  // namespace vilslam
