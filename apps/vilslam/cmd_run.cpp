// `vilslam run --mode vio|vil|lidar-only DATASET --out DIR [--config RUN_YAML] [--realtime SPEED]`: the pipeline,
// offline and deterministic, or with the data released on the wall clock (docs/pipeline.md).
#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "common/progress.h"
#include "common/error.h"
#include "io/dataset.h"
#include "loop/map_file.h"
#include "pipeline/coverage.h"
#include "pipeline/offline_runner.h"
#include "pipeline/run_config.h"
#include "pipeline/run_outputs.h"
#include "pipeline/run_segments.h"
#include "pipeline/run_status.h"
#include "pipeline/timing_stats.h"
#include "vilslam/command.h"
#include "vilslam/dataset_options.h"

namespace {

using namespace vilslam;

struct Options {
  std::string mode = "vio";
  std::string dataset;
  std::string out_dir;
  std::string config_path;
  double realtime_speed = 0.0;
  std::string save_map;
  std::string load_map;
  std::vector<double> reset_at_s;
};

void print_latency(const char* name, const std::vector<double>& samples_ms) {
  const TimingSummary s = summarize_timings(samples_ms);
  std::printf("  %s latency ms: median %.2f p95 %.2f max %.2f (%zu)\n", name, s.median_ms, s.p95_ms, s.max_ms, s.count);
}

void print_realtime(const RealtimeStats& rt) {
  std::printf("real time at %.2fx: dropped stereo pairs %zu, dropped sweeps %zu, reader late by at most %.1f ms\n",
              rt.speed, rt.dropped_frames, rt.dropped_sweeps, rt.max_release_lag_ms);
  print_latency("IMU-rate pose", rt.imu_pose_latency_ms);
  print_latency("camera-rate state", rt.camera_state_latency_ms);
  print_latency("LiDAR pose", rt.lidar_pose_latency_ms);
}

// What the modules went through: each stretch of a non-nominal status (pipeline/run_status.h).
void print_statuses(const OfflineRunResult& r, TimeNs start_t_ns) {
  for (const StatusStretch& s : status_stretches(r)) {
    std::printf("%s %s from %.2f to %.2f s (%zu %s", s.module.c_str(), s.status.c_str(),
                ns_to_s(s.begin_t_ns - start_t_ns), ns_to_s(s.end_t_ns - start_t_ns), s.count,
                s.module == "vio" ? "states" : "sweeps");
    if (s.gap_s > 0) std::printf(", %.2f s without %s", s.gap_s, s.module == "vio" ? "IMU samples" : "sweeps");
    std::printf(")\n");
  }
}

// "coverage of the data span: vio 0.46 (tracking 0.45), lidar 1.00 (tracking 0.97)"
void print_coverage(const RunCoverage& c) {
  std::printf("coverage of the data span:");
  const char* separator = " ";
  for (const auto& [name, module] : {std::pair{"vio", &c.vio}, std::pair{"lidar", &c.lidar}}) {
    if (!*module) continue;
    std::printf("%s%s %.2f (tracking %.2f)", separator, name, (*module)->published, (*module)->tracking);
    separator = ", ";
  }
  std::printf("\n");
}

void print_summary(const OfflineRunResult& r, TimeNs start_t_ns) {
  const TimingSummary fe = summarize_timings(r.frontend_ms);
  const TimingSummary sm = summarize_timings(r.smoother_ms);
  std::printf("%.1f s of data in %.1f s wall (%.2fx real time)\n", r.data_s, r.run_wall_s,
              r.run_wall_s > 0 ? r.data_s / r.run_wall_s : 0.0);
  std::printf("frames %zu, IMU samples %zu, camera states %zu, IMU-rate poses %zu\n", r.matches_per_frame.size(),
              r.imu_samples, r.camera_states.size(), r.imu_poses.size());
  std::printf("frontend ms: median %.2f p95 %.2f max %.2f\n", fe.median_ms, fe.p95_ms, fe.max_ms);
  std::printf("smoother ms: median %.2f p95 %.2f max %.2f\n", sm.median_ms, sm.p95_ms, sm.max_ms);
  if (r.realtime) print_realtime(*r.realtime);
  print_coverage(run_coverage(r));
  print_statuses(r, start_t_ns);
  for (TimeNs t_ns : r.lidar_lost_t_ns) {
    std::printf("LiDAR mapping lost at %.2f s (its last sweeps rejected)\n", ns_to_s(t_ns - start_t_ns));
  }
  if (r.lidar.empty()) return;
  std::vector<double> lidar_ms;
  int degenerate = 0;
  for (const lidar::LidarMappingResult& m : r.lidar) {
    lidar_ms.push_back(m.time_ms);
    degenerate += m.degenerate ? 1 : 0;
  }
  const TimingSummary li = summarize_timings(lidar_ms);
  std::printf("LiDAR sweeps mapped %zu (degenerate %d, rejected %zu, unmapped %zu)\n", r.lidar.size(), degenerate,
              r.lidar_rejected.size(), r.unmapped_scans);
  std::printf("lidar mapping ms: median %.2f p95 %.2f max %.2f\n", li.median_ms, li.p95_ms, li.max_ms);
  if (!r.loop) return;
  std::size_t accepted = 0, untrusted = 0;
  for (const loop::LoopCandidateRecord& c : r.loop->candidates) {
    accepted += c.accepted() ? 1 : 0;
    untrusted += c.rejected_as_untrusted() ? 1 : 0;
  }
  const TimingSummary de = summarize_timings(r.loop->detection_ms);
  const TimingSummary co = summarize_timings(r.loop->correction_ms);
  std::printf("key frames %zu, loop candidates %zu, loops accepted %zu, rejected as untrusted %zu (images matched, "
              "geometry not: loop_candidates.csv)\n",
              r.loop->key_frames, r.loop->candidates.size(), accepted, untrusted);
  std::printf("loop detection + constraints ms: median %.2f p95 %.2f max %.2f; correction ms: median %.2f max %.2f\n",
              de.median_ms, de.p95_ms, de.max_ms, co.median_ms, co.max_ms);
  for (const double ms : r.loop->final_solve_ms) std::printf("final solve with the tilt factors ms: %.2f\n", ms);
  if (r.loop->relocalized_t_ns) {
    std::printf("re-localized in the map at t_ns %lld; %zu map loops in the graph\n",
                static_cast<long long>(*r.loop->relocalized_t_ns), r.loop->map_loops);
  }
  for (std::size_t i = 1; i < r.segments.size(); ++i) {
    const RunSegment& s = r.segments[i];
    std::printf("segment %zu (reset at t_ns %lld): ", i, static_cast<long long>(s.start_t_ns));
    if (s.relocalized_t_ns) {
      std::printf("joined the map %.2f s after the reset\n", ns_to_s(*s.relocalized_t_ns - s.start_t_ns));
    } else {
      std::printf("never re-localized: its poses are in its own frame\n");
    }
  }
}

// --save-map: the map the run extends, loaded and checked before the run so that nothing is written otherwise.
// Empty without --load-map. A map holds one clock, so only a recording that starts after the map's last pose
// extends it (recordings on a robot's wall clock do).
std::optional<loop::SavedMap> load_extensible_map(const std::string& map_dir, const OfflineRunConfig& config,
                                                  const DatasetReader& reader) {
  if (map_dir.empty()) return std::nullopt;
  loop::SavedMap map =
      load_checked_map(map_dir, loop::vocabulary_identity(vocabulary_file(config.vocabulary)), reader.calibration());
  const Trajectory& poses = map.poses;
  if (!poses.empty() && reader.summary().start_t_ns <= poses.back().t_ns) {
    throw InputError("--save-map", "the dataset starts at " + std::to_string(reader.summary().start_t_ns) +
                                       " ns, not after the last pose of " + map_dir + " (" +
                                       std::to_string(poses.back().t_ns) +
                                       " ns): a map holds one clock, so only a later recording extends it");
  }
  return map;
}

// --save-map: the run's key frames and final poses, after the loaded map's when there is one (the loaded map
// extended: the run joins it only once re-localized, its poses then in the map's frame; docs/loop.md).
void save_run_map(const std::string& dir, const OfflineRunConfig& config, const DatasetReader& reader,
                  const OfflineRunResult& result, std::optional<loop::SavedMap> loaded) {
  loop::SavedMap map;
  if (loaded) {
    map = std::move(*loaded);
  } else {
    RigCalibration rig = reader.calibration();
    if (result.time_offset) rig.cam_time_offset_ns = s_to_ns(result.time_offset->offset_s);
    map = empty_map(rig, loop::vocabulary_identity(vocabulary_file(config.vocabulary)));
  }
  const std::size_t before = map.key_frames.size();
  if (!join_map(map, *result.loop)) {
    throw std::runtime_error("the run never re-localized in " + config.load_map +
                             ": its poses are not in the map's frame, so the map was not extended (" + dir +
                             " not written; the run's outputs are)");
  }
  loop::save_map(dir, map);
  std::printf("wrote map %s (%zu key frames, %zu poses; %zu key frames from this run)\n", dir.c_str(),
              map.key_frames.size(), map.poses.size(), map.key_frames.size() - before);
}

vilslam::cli::Command reg("run", "Run the offline pipeline on a dataset and write trajectories and timings",
                          [](CLI::App& app) {
  auto o = std::make_shared<Options>();
  app.add_option("--mode", o->mode, "Pipeline mode")->check(CLI::IsMember({"vio", "vil", "lidar-only"}))->capture_default_str();
  app.add_option("dataset", o->dataset, "Dataset folder (EuRoC, KITTI or the project's format) or ROS1 .bag file")->required();
  const auto bag_args = vilslam::cli::add_dataset_options(app);
  app.add_option("--out", o->out_dir, "Output folder (replaced)")->required();
  app.add_option("--config", o->config_path,
                 "Run YAML with optional sections frontend, vio, lidar_mapper (config/run_default.yaml); default: built-in");
  app.add_option("--realtime", o->realtime_speed,
                 "Release the data on the wall clock at this speed (1 = live) and measure latencies; output not "
                 "deterministic (docs/pipeline.md)")
      ->check(CLI::PositiveNumber);
  app.add_option("--save-map", o->save_map,
                 "Also write the map re-localization needs to this folder (vil with loop closure; docs/formats.md); "
                 "with --load-map, the loaded map extended by this run once it re-localized");
  app.add_option("--load-map", o->load_map,
                 "Re-localize in this saved map and give the LiDAR poses in its frame once there (vil with loop "
                 "closure; docs/loop.md, \"Map reuse\"); the map itself is not changed");
  app.add_option("--reset-at", o->reset_at_s,
                 "Reset the whole state at these times (s from the first event; repeatable): each new segment "
                 "re-localizes in the map of the ones before (vil with loop closure; docs/loop.md, \"Forced resets\")")
      ->excludes("--save-map");
  return [o, bag_args]() {
    OfflineRunConfig config = o->config_path.empty() ? OfflineRunConfig{} : load_run_config(o->config_path);
    config.mode = parse_run_mode(o->mode);
    if (!o->save_map.empty() && (config.mode != RunMode::kVil || !config.loop.enabled)) {
      throw InputError("--save-map", "a map needs --mode vil with loop closure enabled (its key frames)");
    }
    config.load_map = o->load_map;
    config.reset_at_s = o->reset_at_s;
    config.realtime.speed = o->realtime_speed;
    const auto reader = open_dataset(o->dataset, vilslam::cli::dataset_options(*bag_args));
    std::optional<loop::SavedMap> extended;
    if (!o->save_map.empty()) extended = load_extensible_map(config.load_map, config, *reader);
    OfflineRunResult result;
    {
      Progress progress("run", 1.0);
      result = run_offline(*reader, config, [&progress](double fraction) { progress.update(fraction); });
    }
    write_run_outputs(o->out_dir, config, result);
    if (!o->save_map.empty()) save_run_map(o->save_map, config, *reader, result, std::move(extended));
    print_summary(result, reader->summary().start_t_ns);
    if (!config.load_map.empty() && !result.loop->relocalized_t_ns) {
      std::printf("not re-localized in %s: every pose is in the run's own frame\n", config.load_map.c_str());
    }
    std::printf("wrote %s\n", o->out_dir.c_str());
    return 0;
  };
});

}  // namespace
