#include "pipeline/offline_runner.h"

#include <algorithm>
#include <chrono>
#include <ctime>
#include <deque>
#include <filesystem>
#include <limits>
#include <optional>
#include <stdexcept>
#include <type_traits>
#include <variant>

#include <spdlog/spdlog.h>

#include "common/error.h"
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
  System system(calib, config, std::move(callbacks));
  const bool with_vio = config.mode != RunMode::kLidarOnly;

  // Real-time mode: a sweep is released at its end, when a live driver publishes it.
  std::deque<LidarScan> held_sweeps;
  double max_release_lag_ms = 0.0;
  const auto wait_until = [&](TimeNs t_ns) { max_release_lag_ms = std::max(max_release_lag_ms, clock->wait_until(t_ns)); };
  const auto release_until = [&](TimeNs t_ns) {
    while (!held_sweeps.empty() && held_sweeps.front().end_t_ns() <= t_ns) {
      wait_until(held_sweeps.front().end_t_ns());
      system.push_scan(std::move(held_sweeps.front()));
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
  while (auto event = reader.next()) {
    if (progress) progress(double(event->t_ns - summary.start_t_ns) / span_ns);
    if (!first_t_ns) first_t_ns = event->t_ns;
    last_t_ns = event->t_ns;
    if (clock) release_until(event->t_ns);
    bool last_frame_handed_over = false;
    std::visit(
        [&](auto& data) {
          using T = std::decay_t<decltype(data)>;
          if constexpr (std::is_same_v<T, ImuSample>) {
            last_frame_handed_over = frames_read >= summary.stereo_frames && data.t_ns > last_frame_t_ns;
            system.push_imu(data);
          }
          if constexpr (std::is_same_v<T, StereoFrame>) {
            last_frame_t_ns = data.t_ns + calib.cam_time_offset_ns;
            ++frames_read;
            system.push_stereo(std::move(data));
          }
          if constexpr (std::is_same_v<T, LidarScan>) {
            if (clock && config.mode != RunMode::kVio) held_sweeps.push_back(std::move(data));
            else system.push_scan(std::move(data));
          }
        },
        event->data);
    if ((with_vio && last_frame_handed_over) || system.failed()) break;
  }
  if (clock && !system.failed()) release_until(held_sweeps.empty() ? last_t_ns : held_sweeps.back().end_t_ns());
  OfflineRunResult result = system.finish();
  result.time_offset = time_offset;
  if (stats) {
    stats->dropped_frames = system.dropped_frames();
    stats->dropped_sweeps = system.dropped_sweeps();
    stats->max_release_lag_ms = max_release_lag_ms;
    const QueueDepths depths = system.max_queue_depths();
    stats->max_queue_frontend = depths.frontend;
    stats->max_queue_smoother = depths.smoother;
    stats->max_queue_lidar = depths.lidar;
    stats->cpu_s = process_cpu_s() - cpu_start_s;
    result.realtime = std::move(stats);
  }
  result.data_s = first_t_ns ? ns_to_s(last_t_ns - *first_t_ns) : 0.0;
  result.run_wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - run_start).count();
  return result;
}

}  // namespace vilslam
