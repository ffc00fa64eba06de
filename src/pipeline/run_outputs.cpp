#include "pipeline/run_outputs.h"

#include <algorithm>
#include <filesystem>
#include <iomanip>
#include <sstream>

#include "common/json_writer.h"
#include "common/publish_dir.h"
#include "io/trajectory_io.h"
#include "loop/loop_constraints_io.h"
#include "pipeline/coverage.h"
#include "pipeline/run_config.h"
#include "pipeline/run_status.h"
#include "pipeline/timing_stats.h"

namespace vilslam {
namespace {

namespace fs = std::filesystem;

// One module's or one output's per-event times, ms; group: "module" (top level of timings.json), "loop"
// (with the loop closure's counts) or "latency" (inside "realtime").
struct TimingSeries {
  std::string name;
  std::string group;
  std::vector<double> samples_ms;
};

std::vector<TimingSeries> timing_series(const OfflineRunResult& r) {
  std::vector<double> lidar_ms;
  for (const lidar::LidarMappingResult& m : r.lidar) lidar_ms.push_back(m.time_ms);
  std::vector<TimingSeries> series = {
      {"frontend", "module", r.frontend_ms}, {"smoother", "module", r.smoother_ms}, {"lidar_mapping", "module", lidar_ms}};
  if (r.loop) {
    series.push_back({"key_frame", "loop", r.loop->key_frame_ms});
    series.push_back({"loop_detection_and_constraints", "loop", r.loop->detection_ms});
    series.push_back({"loop_correction", "loop", r.loop->correction_ms});
    series.push_back({"loop_final_solve", "loop", r.loop->final_solve_ms});
  }
  if (r.realtime) {
    series.push_back({"imu_pose_latency", "latency", r.realtime->imu_pose_latency_ms});
    series.push_back({"camera_state_latency", "latency", r.realtime->camera_state_latency_ms});
    series.push_back({"lidar_pose_latency", "latency", r.realtime->lidar_pose_latency_ms});
  }
  return series;
}

// The summaries of one group's series, each as "name": {frames, median_ms, p95_ms, max_ms}.
void write_timings(JsonWriter& json, const std::vector<TimingSeries>& series, const std::string& group) {
  for (const TimingSeries& t : series) {
    if (t.group != group) continue;
    const TimingSummary s = summarize_timings(t.samples_ms);
    json.key(t.name).begin_object();
    json.key("frames").value(static_cast<std::uint64_t>(s.count));
    json.key("median_ms").value(s.median_ms);
    json.key("p95_ms").value(s.p95_ms);
    json.key("max_ms").value(s.max_ms);
    json.end_object();
  }
}

std::string timings_json(RunMode mode, const OfflineRunResult& r, const std::vector<TimingSeries>& series) {
  JsonWriter json;
  json.begin_object();
  json.key("mode").value(run_mode_name(mode));
  json.key("data_s").value(r.data_s);
  json.key("run_wall_s").value(r.run_wall_s);
  json.key("stereo_frames").value(static_cast<std::uint64_t>(r.matches_per_frame.size()));
  json.key("imu_samples").value(static_cast<std::uint64_t>(r.imu_samples));
  json.key("camera_states").value(static_cast<std::uint64_t>(r.camera_states.size()));
  json.key("imu_poses").value(static_cast<std::uint64_t>(r.imu_poses.size()));
  const auto [min_it, max_it] = std::minmax_element(r.matches_per_frame.begin(), r.matches_per_frame.end());
  json.key("matches_min").value(min_it == r.matches_per_frame.end() ? 0 : *min_it);
  json.key("matches_max").value(max_it == r.matches_per_frame.end() ? 0 : *max_it);
  write_timings(json, series, "module");
  // The fraction of the data span each module covered with published poses, and with tracking ones.
  const RunCoverage coverage = run_coverage(r);
  json.key("coverage").begin_object();
  for (const auto& [name, module] : {std::pair{"vio", &coverage.vio}, std::pair{"lidar", &coverage.lidar}}) {
    if (!*module) continue;
    json.key(name).begin_object();
    json.key("published").value((*module)->published);
    json.key("tracking").value((*module)->tracking);
    json.end_object();
  }
  json.end_object();
  json.key("lidar_unmapped_scans").value(static_cast<std::uint64_t>(r.unmapped_scans));
  json.key("lidar_rejected_scans").value(static_cast<std::uint64_t>(r.lidar_rejected.size()));
  json.key("lidar_lost_t_ns").begin_array();
  for (TimeNs t_ns : r.lidar_lost_t_ns) json.value(static_cast<std::int64_t>(t_ns));
  json.end_array();
  if (r.loop) {
    json.key("key_frames").value(static_cast<std::uint64_t>(r.loop->key_frames));
    json.key("loop_candidates").value(static_cast<std::uint64_t>(r.loop->candidates.size()));
    const auto accepted = std::count_if(r.loop->candidates.begin(), r.loop->candidates.end(),
                                        [](const loop::LoopCandidateRecord& c) { return c.accepted(); });
    json.key("loops_accepted").value(static_cast<std::uint64_t>(accepted));
    const auto untrusted = std::count_if(r.loop->candidates.begin(), r.loop->candidates.end(),
                                         [](const loop::LoopCandidateRecord& c) { return c.rejected_as_untrusted(); });
    json.key("loops_rejected").value(static_cast<std::uint64_t>(untrusted));
    write_timings(json, series, "loop");
  }
  if (r.realtime) {
    json.key("realtime").begin_object();
    json.key("speed").value(r.realtime->speed);
    json.key("dropped_stereo_pairs").value(static_cast<std::uint64_t>(r.realtime->dropped_frames));
    json.key("dropped_sweeps").value(static_cast<std::uint64_t>(r.realtime->dropped_sweeps));
    json.key("max_release_lag_ms").value(r.realtime->max_release_lag_ms);
    json.key("max_queue_depth").begin_object();
    const QueueDepths& depth = r.realtime->max_queue_depth;
    json.key("frontend").value(static_cast<std::uint64_t>(depth.frontend));
    json.key("smoother").value(static_cast<std::uint64_t>(depth.smoother));
    json.key("lidar").value(static_cast<std::uint64_t>(depth.lidar));
    json.end_object();
    json.key("cpu_s").value(r.realtime->cpu_s);
    json.key("cpu_cores_used").value(r.run_wall_s > 0 ? r.realtime->cpu_s / r.run_wall_s : 0.0);
    write_timings(json, series, "latency");
    json.end_object();
  }
  json.end_object();
  return json.str();
}

// timing_samples.csv: every sample behind the summaries of timings.json, one row each: series,ms (in event order).
std::string timing_samples_csv(const std::vector<TimingSeries>& series) {
  std::ostringstream out;
  out << std::setprecision(9) << "series,ms\n";
  for (const TimingSeries& t : series) {
    for (double ms : t.samples_ms) out << t.name << ',' << ms << '\n';
  }
  return out.str();
}

// time_offset_online.csv: every online estimate of the camera-IMU time offset and the offset it set, one row each.
std::string time_offset_online_csv(const std::vector<OnlineTimeOffsetUpdate>& updates) {
  std::ostringstream out;
  out << std::setprecision(17) << "t_ns,cam_time_offset_s,applied_offset_s,intervals,rms_rad,rms_zero_offset_rad\n";
  for (const OnlineTimeOffsetUpdate& u : updates) {
    out << u.t_ns << ',' << u.estimate.offset_s << ',' << u.applied_offset_s << ',' << u.estimate.intervals << ','
        << u.estimate.rms_rad << ',' << u.estimate.rms_zero_offset_rad << '\n';
  }
  return out.str();
}

// The estimated camera-IMU time offset (t_imu = t_cam + offset) and how well it explains the rotations.
std::string time_offset_json(const TimeOffsetEstimate& e) {
  JsonWriter json;
  json.begin_object();
  json.key("cam_time_offset_s").value(e.offset_s);
  json.key("cam_time_offset_ns").value(static_cast<std::int64_t>(s_to_ns(e.offset_s)));
  json.key("gyro_bias_rad_s").begin_array();
  for (int i = 0; i < 3; ++i) json.value(e.gyro_bias_rad_s(i));
  json.end_array();
  json.key("intervals").value(e.intervals);
  json.key("rms_rad").value(e.rms_rad);
  json.key("rms_zero_offset_rad").value(e.rms_zero_offset_rad);
  json.end_object();
  return json.str();
}

// Whether and when the run re-localized in the loaded map, where its own frame lay in the map's then (T_map_run:
// translation and quaternion x y z w, as TUM rows), and the map candidates examined and accepted.
// A pose as [x, y, z, qx, qy, qz, qw] (TUM's order).
void write_pose(JsonWriter& json, const SE3& T) {
  const Vec3& t = T.translation();
  const Quat& q = T.quat();
  json.begin_array();
  for (double v : {t.x(), t.y(), t.z(), q.x(), q.y(), q.z(), q.w()}) json.value(v);
  json.end_array();
}

std::string relocalization_json(const std::string& map_dir, const LoopClosureOutput& loop,
                                const std::vector<loop::LoopCandidateRecord>& map_candidates) {
  std::size_t accepted = 0;
  for (const loop::LoopCandidateRecord& c : map_candidates) accepted += c.accepted() ? 1 : 0;
  JsonWriter json;
  json.begin_object();
  json.key("map").value(map_dir);
  json.key("relocalized").value(loop.relocalized_t_ns.has_value());
  if (loop.relocalized_t_ns) {
    json.key("relocalized_t_ns").value(static_cast<std::int64_t>(*loop.relocalized_t_ns));
    json.key("T_map_run");
    write_pose(json, loop.T_map_run);
  }
  json.key("map_candidates").value(static_cast<std::uint64_t>(map_candidates.size()));
  json.key("map_candidates_accepted").value(static_cast<std::uint64_t>(accepted));
  json.key("map_loops_in_graph").value(static_cast<std::uint64_t>(loop.map_loops));
  json.end_object();
  return json.str();
}

// A run with resets: each segment, and when it joined the map of the ones before (docs/formats.md).
std::string segments_json(const std::vector<RunSegment>& segments) {
  JsonWriter json;
  json.begin_object();
  json.key("segments").begin_array();
  for (const RunSegment& s : segments) {
    json.begin_object();
    json.key("start_t_ns").value(static_cast<std::int64_t>(s.start_t_ns));
    json.key("sweeps").value(static_cast<std::uint64_t>(s.sweeps));
    json.key("key_frames").value(static_cast<std::uint64_t>(s.key_frames));
    json.key("relocalized").value(s.relocalized_t_ns.has_value());
    if (s.relocalized_t_ns) {
      json.key("relocalized_t_ns").value(static_cast<std::int64_t>(*s.relocalized_t_ns));
      json.key("T_map_run");
      write_pose(json, s.T_map_run);
    }
    json.key("map_candidates").value(static_cast<std::uint64_t>(s.map_candidates));
    json.key("map_candidates_accepted").value(static_cast<std::uint64_t>(s.map_candidates_accepted));
    json.key("map_loops_in_graph").value(static_cast<std::uint64_t>(s.map_loops));
    json.end_object();
  }
  json.end_array();
  json.end_object();
  return json.str();
}

// One row per mapped sweep: t_ns, degenerate (0/1), the six eigenvalues of J^T J in ascending order, and
// the registration's fit (rms residual, matched and inlier fractions).
std::string degeneracy_csv(const std::vector<lidar::LidarMappingResult>& mapped) {
  std::ostringstream out;
  out << std::setprecision(17)
      << "t_ns,degenerate,eig0,eig1,eig2,eig3,eig4,eig5,rms_residual_m,matched_fraction,inlier_fraction\n";
  for (const lidar::LidarMappingResult& m : mapped) {
    out << m.t_ns << ',' << (m.degenerate ? 1 : 0);
    for (int i = 0; i < 6; ++i) out << ',' << m.information_eigenvalues[i];
    out << ',' << m.rms_residual_m << ',' << m.matched_fraction << ',' << m.inlier_fraction << '\n';
  }
  return out.str();
}

}  // namespace

void write_run_outputs(const std::string& out_dir, const OfflineRunConfig& config, const OfflineRunResult& result) {
  const RunMode mode = config.mode;
  fs::path out = fs::path(out_dir).lexically_normal();
  if (!out.has_filename()) out = out.parent_path();  // "DIR/"
  const fs::path partial = out.string() + ".partial";
  fs::remove_all(partial);
  fs::create_directories(partial);
  if (mode != RunMode::kLidarOnly) {
    write_trajectory((partial / "vio_camera.tum").string(), result.camera_states, TrajectoryFormat::kTum);
    write_trajectory((partial / "vio_imu.tum").string(), result.imu_poses, TrajectoryFormat::kTum);
    write_file_atomic((partial / "vio_status.csv").string(), vio_status_csv(result.vio_status));
    if (result.realtime) {
      write_trajectory((partial / "vio_imu_live.tum").string(), result.realtime->live_imu_poses, TrajectoryFormat::kTum);
    }
  }
  if (mode != RunMode::kVio) {
    if (!result.lidar_sensor.empty()) write_file_atomic((partial / "lidar_sensor.txt").string(), result.lidar_sensor);
    if (result.loop) {
      // With the loop closure module (vil): the odometry, the poses as published, the final graph.
      write_trajectory((partial / "lidar.tum").string(), result.loop->lidar_odometry, TrajectoryFormat::kTum);
      write_trajectory((partial / "lidar_global.tum").string(), result.loop->lidar_global, TrajectoryFormat::kTum);
      write_trajectory((partial / "lidar_final.tum").string(), result.loop->lidar_final, TrajectoryFormat::kTum);
      // This run's loops; a loaded map's candidates apart (their times are on the map's clock).
      std::vector<loop::LoopCandidateRecord> own, in_map;
      for (const loop::LoopCandidateRecord& c : result.loop->candidates) (c.map_candidate ? in_map : own).push_back(c);
      write_file_atomic((partial / "loops.csv").string(), loop::loops_csv(own));
      write_file_atomic((partial / "loop_candidates.csv").string(), loop::loop_candidates_csv(own));
      if (!config.load_map.empty() || !result.segments.empty()) {
        write_file_atomic((partial / "map_candidates.csv").string(), loop::loop_candidates_csv(in_map));
      }
      if (!config.load_map.empty()) {
        write_file_atomic((partial / "relocalization.json").string(), relocalization_json(config.load_map, *result.loop, in_map));
      }
      if (!result.segments.empty()) {
        write_file_atomic((partial / "segments.json").string(), segments_json(result.segments));
      }
    } else {
      Trajectory T_W_L;
      for (const lidar::LidarMappingResult& m : result.lidar) T_W_L.push_back({m.t_ns, m.T_W_L});
      write_trajectory((partial / "lidar.tum").string(), T_W_L, TrajectoryFormat::kTum);
    }
    write_file_atomic((partial / "degeneracy.csv").string(), degeneracy_csv(result.lidar));
    write_file_atomic((partial / "lidar_status.csv").string(), lidar_status_csv(result.lidar, result.lidar_rejected));
  }
  const std::vector<TimingSeries> series = timing_series(result);
  write_file_atomic((partial / "timings.json").string(), timings_json(mode, result, series));
  write_file_atomic((partial / "timing_samples.csv").string(), timing_samples_csv(series));
  if (result.time_offset) write_file_atomic((partial / "time_offset.json").string(), time_offset_json(*result.time_offset));
  if (!result.time_offset_online.empty()) {
    write_file_atomic((partial / "time_offset_online.csv").string(), time_offset_online_csv(result.time_offset_online));
  }
  write_file_atomic((partial / "config.yaml").string(), run_config_yaml(config));
  publish_directory(partial.string(), out);
}

}  // namespace vilslam
