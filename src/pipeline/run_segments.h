#pragma once
// A run cut into segments by resets of the whole state (run --reset-at, docs/loop.md "Forced resets"; or after
// LiDAR mapping was lost, docs/pipeline.md "Resets after a lost map"): each segment starts a new System, which
// re-localizes in the map of the segments before it (the map-reuse machinery, in memory). These put a segment's
// outputs after the earlier ones' and grow that map.
#include <cstdint>
#include <optional>
#include <string>

#include "common/calibration.h"
#include "loop/map_file.h"
#include "pipeline/run_types.h"

namespace vilslam {

// The saved map in dir, checked to fit the run's vocabulary and rig (loop::load_map, loop::check_map_fits).
loop::SavedMap load_checked_map(const std::string& dir, std::uint64_t vocabulary_id, const RigCalibration& rig);

// An empty map of this rig and vocabulary (vocabulary_identity of its file).
loop::SavedMap empty_map(const RigCalibration& rig, std::uint64_t vocabulary_id);

// Appends a run's (or a segment's) key frames and final poses to the map. The first run defines the map's
// frame; a later one joins only when it re-localized in the map (its final poses are then in the map's frame):
// returns false, and leaves the map as it was, when it did not. Needs the run's loop closure output.
bool join_map(loop::SavedMap& map, const LoopClosureOutput& run);

// Appends a segment's outputs to the run so far: trajectories, per-frame and per-sweep series, loop
// candidates and key frames one after the other (each segment's VIO and odometry in its own frame, its
// final poses in the map's once re-localized), counts added up, and the segment's entry in run.segments.
// start_t_ns: the instant the segment's data begins.
void append_segment(OfflineRunResult& run, OfflineRunResult&& segment, TimeNs start_t_ns);

// A run as its Systems one after the other (the offline runner's, the live node's). Until the first reset it is a
// single System's run, with no map and no segments.
class RunSegments {
 public:
  // first_t_ns: the run's first event. config.load_map: a saved map the run starts in, or none.
  RunSegments(const RigCalibration& rig, const OfflineRunConfig& config, TimeNs first_t_ns);

  // The current segment ends with its System's outputs, and the next begins at t_ns. Returns the map of every
  // segment so far, for the next System (given restart_config()).
  const loop::SavedMap& reset(OfflineRunResult&& segment, TimeNs t_ns);
  // The last segment ends: the whole run.
  OfflineRunResult finish(OfflineRunResult&& segment);

  // The config of a System after a reset: the robot is likely moving, so the VIO aligns in motion.
  const OfflineRunConfig& restart_config() const { return restart_config_; }

 private:
  void close(OfflineRunResult&& segment);

  RigCalibration rig_;
  OfflineRunConfig restart_config_;
  TimeNs first_t_ns_;
  TimeNs segment_start_t_ns_;
  std::optional<loop::SavedMap> map_;
  OfflineRunResult run_;
};

}  // namespace vilslam
