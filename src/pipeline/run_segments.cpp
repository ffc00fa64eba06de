#include "pipeline/run_segments.h"

#include <algorithm>
#include <stdexcept>

#include <spdlog/spdlog.h>

namespace vilslam {
namespace {

template <typename T>
void append(std::vector<T>& to, std::vector<T>&& from) {
  to.insert(to.end(), std::make_move_iterator(from.begin()), std::make_move_iterator(from.end()));
}

// The key frames' pose indices, moved behind `offset` poses already there.
void append_key_frames(std::vector<loop::KeyFrame>& to, std::vector<loop::KeyFrame>&& from, std::size_t offset) {
  for (loop::KeyFrame& k : from) k.pose_index += offset;
  append(to, std::move(from));
}

RunSegment segment_entry(const OfflineRunResult& segment, TimeNs start_t_ns) {
  RunSegment s;
  s.start_t_ns = start_t_ns;
  s.sweeps = segment.lidar.size();
  if (!segment.loop) return s;
  const LoopClosureOutput& loop = *segment.loop;
  s.key_frames = loop.key_frames;
  s.relocalized_t_ns = loop.relocalized_t_ns;
  s.T_map_run = loop.T_map_run;
  s.map_loops = loop.map_loops;
  for (const loop::LoopCandidateRecord& c : loop.candidates) {
    if (!c.map_candidate) continue;
    ++s.map_candidates;
    if (c.accepted()) ++s.map_candidates_accepted;
  }
  return s;
}

}  // namespace

loop::SavedMap load_checked_map(const std::string& dir, std::uint64_t vocabulary_id, const RigCalibration& rig) {
  loop::SavedMap map = loop::load_map(dir);
  loop::check_map_fits(map, dir, vocabulary_id, rig);
  return map;
}

loop::SavedMap empty_map(const RigCalibration& rig, std::uint64_t vocabulary_id) {
  loop::SavedMap map;
  map.rig = rig;
  map.vocabulary_id = vocabulary_id;
  return map;
}

bool join_map(loop::SavedMap& map, const LoopClosureOutput& run) {
  if (!map.poses.empty() && !run.relocalized_t_ns) return false;
  if (!map.poses.empty() && !run.lidar_final.empty() && run.lidar_final.front().t_ns <= map.poses.back().t_ns) {
    throw std::invalid_argument("join_map: the run begins before the map's last pose");
  }
  std::vector<loop::KeyFrame> key_frames = run.key_frame_data;
  append_key_frames(map.key_frames, std::move(key_frames), map.poses.size());
  map.poses.insert(map.poses.end(), run.lidar_final.begin(), run.lidar_final.end());
  return true;
}

void append_segment(OfflineRunResult& run, OfflineRunResult&& segment, TimeNs start_t_ns) {
  run.segments.push_back(segment_entry(segment, start_t_ns));
  append(run.camera_states, std::move(segment.camera_states));
  append(run.vio_status, std::move(segment.vio_status));
  append(run.imu_poses, std::move(segment.imu_poses));
  append(run.imu_motion, std::move(segment.imu_motion));
  append(run.matches_per_frame, std::move(segment.matches_per_frame));
  append(run.frontend_ms, std::move(segment.frontend_ms));
  append(run.smoother_ms, std::move(segment.smoother_ms));
  append(run.time_offset_online, std::move(segment.time_offset_online));
  run.imu_samples += segment.imu_samples;
  append(run.lidar, std::move(segment.lidar));
  append(run.lidar_rejected, std::move(segment.lidar_rejected));
  append(run.lidar_lost_t_ns, std::move(segment.lidar_lost_t_ns));
  run.unmapped_scans += segment.unmapped_scans;
  if (run.lidar_sensor.empty()) run.lidar_sensor = std::move(segment.lidar_sensor);
  if (segment.loop) {
    if (!run.loop) run.loop.emplace();
    LoopClosureOutput& to = *run.loop;
    LoopClosureOutput& from = *segment.loop;
    // The first segment's re-localization (in a loaded map) stays the run's; the later ones are in run.segments.
    if (run.segments.size() == 1) {
      to.relocalized_t_ns = from.relocalized_t_ns;
      to.T_map_run = from.T_map_run;
    }
    append_key_frames(to.key_frame_data, std::move(from.key_frame_data), to.lidar_final.size());
    append(to.lidar_odometry, std::move(from.lidar_odometry));
    append(to.lidar_global, std::move(from.lidar_global));
    append(to.lidar_final, std::move(from.lidar_final));
    append(to.candidates, std::move(from.candidates));
    to.key_frames += from.key_frames;
    append(to.key_frame_ms, std::move(from.key_frame_ms));
    append(to.detection_ms, std::move(from.detection_ms));
    append(to.correction_ms, std::move(from.correction_ms));
    append(to.final_solve_ms, std::move(from.final_solve_ms));
    to.map_loops += from.map_loops;
  }
}

RunSegments::RunSegments(const RigCalibration& rig, const OfflineRunConfig& config, TimeNs first_t_ns)
    : rig_(rig), restart_config_(config), first_t_ns_(first_t_ns), segment_start_t_ns_(first_t_ns) {
  restart_config_.vio.initializer.moving_start = true;
}

void RunSegments::close(OfflineRunResult&& segment) {
  if (!map_) {
    const std::uint64_t vocabulary_id = loop::vocabulary_identity(vocabulary_file(restart_config_.vocabulary));
    const std::string& loaded = restart_config_.load_map;
    map_ = loaded.empty() ? empty_map(rig_, vocabulary_id) : load_checked_map(loaded, vocabulary_id, rig_);
  }
  if (!segment.loop || !join_map(*map_, *segment.loop)) {
    spdlog::warn("the segment from {:.3f} s never re-localized: its poses stay in its own frame, out of the map",
                 ns_to_s(segment_start_t_ns_ - first_t_ns_));
  }
  append_segment(run_, std::move(segment), segment_start_t_ns_);
}

const loop::SavedMap& RunSegments::reset(OfflineRunResult&& segment, TimeNs t_ns) {
  close(std::move(segment));
  segment_start_t_ns_ = t_ns;
  return *map_;
}

OfflineRunResult RunSegments::finish(OfflineRunResult&& segment) {
  if (!map_) return std::move(segment);
  close(std::move(segment));
  return std::move(run_);
}

}  // namespace vilslam
