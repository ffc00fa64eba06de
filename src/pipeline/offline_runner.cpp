#include "pipeline/offline_runner.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>
#include <deque>
#include <memory>
#include <filesystem>
#include <limits>
#include <optional>
#include <stdexcept>
#include <type_traits>
#include <variant>

#include <spdlog/spdlog.h>

#include "common/error.h"
#include "loop/map_file.h"
#include "pipeline/run_segments.h"
#include "pipeline/system.h"
#include "pipeline/time_offset_pass.h"

namespace vilslam {
namespace {

void check_mode_fits(const DatasetReader& reader, RunMode mode) {
  const DatasetSummary& s = reader.summary();
  const std::string name = run_mode_name(mode);
  if (mode != RunMode::kLidarOnly && (s.format == "kitti" || s.stereo_frames == 0 || s.imu_samples == 0)) {
    throw InputError(s.path, "mode " + name + " needs stereo images and IMU samples; this " + s.format + " dataset has " +
                                 std::to_string(s.stereo_frames) + " frames and " + std::to_string(s.imu_samples) +
                                 " IMU samples (use --mode lidar-only)");
  }
  if (mode != RunMode::kVio && (s.lidar_scans == 0 || !reader.calibration().has_lidar)) {
    throw InputError(s.path, "mode " + name + " needs LiDAR scans and a LiDAR calibration; this " + s.format +
                                 " dataset has " + std::to_string(s.lidar_scans) + " scans");
  }
}

void check_resets(const OfflineRunConfig& config) {
  if (config.reset_at_s.empty()) return;
  if (config.mode != RunMode::kVil || !config.loop.enabled) {
    throw InputError("--reset-at", "a reset re-localizes in the map built before it: mode vil with loop closure enabled");
  }
  double previous_s = 0.0;
  for (double t_s : config.reset_at_s) {
    if (!std::isfinite(t_s) || t_s <= previous_s) {
      throw InputError("--reset-at", "reset times must be finite, positive and increasing (seconds from the first event)");
    }
    previous_s = t_s;
  }
}

// CPU time of the whole process, every thread, in seconds.
double process_cpu_s() { return static_cast<double>(std::clock()) / CLOCKS_PER_SEC; }

}  // namespace

std::string default_vocabulary_path() {
  // The source tree's file while it exists (build tree, tests), else the copy `cmake --install` put in place.
  return std::filesystem::exists(VILSLAM_DEFAULT_VOCABULARY) ? VILSLAM_DEFAULT_VOCABULARY : VILSLAM_INSTALLED_VOCABULARY;
}

std::string vocabulary_file(const std::string& name) { return name == "default" ? default_vocabulary_path() : name; }

RunMode parse_run_mode(const std::string& name) {
  if (name == "vio") return RunMode::kVio;
  if (name == "vil") return RunMode::kVil;
  if (name == "lidar-only") return RunMode::kLidarOnly;
  throw std::invalid_argument("unknown run mode '" + name + "' (vio | vil | lidar-only)");
}

std::string run_mode_name(RunMode mode) {
  switch (mode) {
    case RunMode::kVio: return "vio";
    case RunMode::kVil: return "vil";
    case RunMode::kLidarOnly: return "lidar-only";
  }
  return {};
}

OfflineRunResult run_offline(DatasetReader& reader, const OfflineRunConfig& config,
                             const std::function<void(double)>& progress) {
  check_mode_fits(reader, config.mode);
  check_resets(config);
  const auto run_start = std::chrono::steady_clock::now();
  const double cpu_start_s = process_cpu_s();
  const DatasetSummary& summary = reader.summary();
  RigCalibration calib = reader.calibration();
  std::optional<TimeOffsetEstimate> time_offset;
  if (config.time_offset.enabled && config.mode != RunMode::kLidarOnly) {
    time_offset = estimate_sequence_time_offset(reader, config.frontend, config.time_offset);
    if (time_offset) {
      calib.cam_time_offset_ns = s_to_ns(time_offset->offset_s);
      spdlog::info("camera-IMU time offset {:.2f} ms (t_imu = t_cam + offset) from {} intervals, residual {:.5f} "
                   "rad ({:.5f} at 0)",
                   1e3 * time_offset->offset_s, time_offset->intervals, time_offset->rms_rad,
                   time_offset->rms_zero_offset_rad);
    } else {
      spdlog::warn("camera-IMU time offset not observable in the first {} s (too little rotation or tracking); "
                   "keeping the calibration's {} ns",
                   config.time_offset.window_s, calib.cam_time_offset_ns);
    }
  }
  // Real-time mode: each output's latency, taken by the callbacks on the modules' threads (each series is
  // written by one thread only).
  std::optional<RealtimeStats> stats;
  std::optional<SensorClock> clock;
  SystemCallbacks callbacks;
  if (config.realtime.speed > 0.0) {
    stats.emplace();
    stats->speed = config.realtime.speed;
    clock.emplace(summary.start_t_ns, config.realtime.speed);
    RealtimeStats* rt = &*stats;
    const SensorClock* c = &*clock;
    callbacks.imu_pose = [rt, c](const TimedPose& p) {
      rt->live_imu_poses.push_back(p);
      rt->imu_pose_latency_ms.push_back(c->since_ms(p.t_ns));
    };
    callbacks.camera_state = [rt, c](const TimedPose& p) { rt->camera_state_latency_ms.push_back(c->since_ms(p.t_ns)); };
    callbacks.lidar_pose = [rt, c](const lidar::LidarMappingResult& r) {
      rt->lidar_pose_latency_ms.push_back(c->since_ms(r.t_ns));
    };
  }
  // Resets (run --reset-at): each segment is a new System, re-localizing in the map of the ones before it.
  std::vector<TimeNs> resets_ns;
  for (double reset_s : config.reset_at_s) resets_ns.push_back(summary.start_t_ns + s_to_ns(reset_s));
  // Resets decided by the run (config.reset_on_lidar_lost): checked every reset_check_s of data.
  const bool reset_on_lost = resets_on_lidar_lost(config);
  const TimeNs check_period_ns = std::max<TimeNs>(1, s_to_ns(config.reset_check_s));
  RunSegments segments(calib, config, summary.start_t_ns);
  auto system = std::make_unique<System>(calib, config, callbacks);
  std::size_t dropped_frames = 0, dropped_sweeps = 0;
  QueueDepths depths;
  const auto end_system = [&]() {
    dropped_frames += system->dropped_frames();
    dropped_sweeps += system->dropped_sweeps();
    const QueueDepths d = system->max_queue_depths();
    depths = {std::max(depths.frontend, d.frontend), std::max(depths.smoother, d.smoother), std::max(depths.lidar, d.lidar)};
    return system->finish();
  };
  const bool with_vio = config.mode != RunMode::kLidarOnly;

  // Real-time mode: a sweep is released at its end, when a live driver publishes it.
  std::deque<LidarScan> held_sweeps;
  double max_release_lag_ms = 0.0;
  const auto wait_until = [&](TimeNs t_ns) { max_release_lag_ms = std::max(max_release_lag_ms, clock->wait_until(t_ns)); };
  const auto release_until = [&](TimeNs t_ns) {
    while (!held_sweeps.empty() && held_sweeps.front().end_t_ns() <= t_ns) {
      wait_until(held_sweeps.front().end_t_ns());
      system->push_scan(std::move(held_sweeps.front()));
      held_sweeps.pop_front();
    }
    wait_until(t_ns);
  };

  reader.rewind();
  if (clock) clock->restart();
  // The IMU stream may run on long after the last image (EuRoC slices): stop at the first IMU sample after
  // the last frame, which hands that frame to the smoother.
  std::size_t frames_read = 0;
  TimeNs last_frame_t_ns = std::numeric_limits<TimeNs>::max();
  const double span_ns = std::max<double>(1.0, double(summary.end_t_ns - summary.start_t_ns));
  std::optional<TimeNs> first_t_ns;
  TimeNs last_t_ns = 0;
  std::size_t next_reset = 0;
  TimeNs next_check_ns = summary.start_t_ns + check_period_ns;
  while (auto event = reader.next()) {
    if (progress) progress(double(event->t_ns - summary.start_t_ns) / span_ns);
    if (!first_t_ns) first_t_ns = event->t_ns;
    last_t_ns = event->t_ns;
    if (clock) release_until(event->t_ns);
    std::optional<TimeNs> reset_ns;
    if (next_reset < resets_ns.size() && event->t_ns >= resets_ns[next_reset]) reset_ns = resets_ns[next_reset++];
    bool lost = false;
    for (; reset_on_lost && !reset_ns && event->t_ns >= next_check_ns; next_check_ns += check_period_ns) {
      // Offline the modules catch up first, so that what they decided depends on the data before the check only.
      if (!clock) system->wait_idle();
      lost = system->lidar_lost();
      if (lost) reset_ns = next_check_ns;
    }
    if (reset_ns) {
      // Everything before the reset is forgotten but the map: a sweep still held (it began before) is lost.
      held_sweeps.clear();
      const loop::SavedMap& map = segments.reset(end_system(), *reset_ns);
      next_check_ns = *reset_ns + check_period_ns;
      spdlog::info("reset of the whole state at {:.3f} s{}", ns_to_s(*reset_ns - summary.start_t_ns),
                   lost ? " (LiDAR mapping was lost)" : "");
      system = std::make_unique<System>(calib, segments.restart_config(), callbacks, map);
    }
    bool last_frame_handed_over = false;
    std::visit(
        [&](auto& data) {
          using T = std::decay_t<decltype(data)>;
          if constexpr (std::is_same_v<T, ImuSample>) {
            last_frame_handed_over = frames_read >= summary.stereo_frames && data.t_ns > last_frame_t_ns;
            system->push_imu(data);
          }
          if constexpr (std::is_same_v<T, StereoFrame>) {
            // Online the offset may move by up to max_abs_offset_s from the calibration's.
            last_frame_t_ns = data.t_ns + calib.cam_time_offset_ns +
                              (config.time_offset.online ? s_to_ns(config.time_offset.max_abs_offset_s) : 0);
            ++frames_read;
            system->push_stereo(std::move(data));
          }
          if constexpr (std::is_same_v<T, LidarScan>) {
            if (clock && config.mode != RunMode::kVio) held_sweeps.push_back(std::move(data));
            else system->push_scan(std::move(data));
          }
        },
        event->data);
    if ((with_vio && last_frame_handed_over) || system->failed()) break;
  }
  if (clock && !system->failed()) release_until(held_sweeps.empty() ? last_t_ns : held_sweeps.back().end_t_ns());
  OfflineRunResult result = segments.finish(end_system());
  result.time_offset = time_offset;
  if (!result.time_offset_online.empty()) {
    const OnlineTimeOffsetUpdate& last = result.time_offset_online.back();
    spdlog::info("camera-IMU time offset estimated online: {:.3f} ms at the last of {} estimates ({} intervals)",
                 1e3 * last.applied_offset_s, result.time_offset_online.size(), last.estimate.intervals);
  }
  if (stats) {
    stats->dropped_frames = dropped_frames;
    stats->dropped_sweeps = dropped_sweeps;
    stats->max_release_lag_ms = max_release_lag_ms;
    stats->max_queue_depth = depths;
    stats->cpu_s = process_cpu_s() - cpu_start_s;
    result.realtime = std::move(stats);
  }
  result.data_s = first_t_ns ? ns_to_s(last_t_ns - *first_t_ns) : 0.0;
  result.run_wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - run_start).count();
  return result;
}

}  // namespace vilslam
