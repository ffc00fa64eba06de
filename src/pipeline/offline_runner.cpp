#include "pipeline/offline_runner.h"

#include <algorithm>
#include <chrono>
#include <deque>
#include <limits>
#include <optional>
#include <stdexcept>
#include <type_traits>
#include <variant>

#include <spdlog/spdlog.h>

#include "common/error.h"
#include "frontend/frontend.h"
#include "pipeline/lidar_feeder.h"
#include "pipeline/live_propagator.h"
#include "pipeline/stage.h"
#include "pipeline/time_offset_pass.h"

namespace vilslam {
namespace {

double elapsed_ms(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

// What the LiDAR side receives, in the dataset's order: stereo pairs (key images, on the IMU clock), sweeps,
// and after each IMU sample the IMU-rate poses the VIO published for it (none before initialization).
struct PosesAdvanced {
  Trajectory imu_poses;   // T_W_I
  Trajectory imu_motion;  // T_O_I at the same samples
};
using LidarMessage = std::variant<PosesAdvanced, StereoFrame, LidarScan>;

// A stereo pair on the IMU clock with its frontend output.
struct TrackedFrame {
  StereoFrame frame;
  FrontendOutput out;
};
using VioMessage = std::variant<ImuSample, TrackedFrame, LidarScan>;
using FrontendMessage = std::variant<ImuSample, StereoFrame, LidarScan>;

// What the modules see of the real-time mode (none offline): the clock, the load the overload policy reads, and
// the statistics each module's thread adds to (every field is written by one thread only).
struct RealtimeContext {
  RealtimeContext(TimeNs first_t_ns, const OfflineRunConfig& config, const RigCalibration& calib,
                  RealtimeStats* stats_out)
      : clock(first_t_ns, config.realtime.speed), load(config.realtime),
        live(calib.imu, Vec3(0, 0, -config.vio.smoother.gravity_m_s2)), stats(stats_out) {}
  SensorClock clock;
  PipelineLoad load;
  LivePropagator live;  // the IMU-rate poses published as the samples arrive
  RealtimeStats* stats;
};

// LiDAR mapping and loop closure (paper: the LiDAR mapping and loop closure threads). Keeps its own copy of
// the VIO's IMU-rate poses, grown exactly as the VIO published them, so it never reads the VIO's memory.
class LidarSide {
 public:
  LidarSide(const RigCalibration& calib, const OfflineRunConfig& config, OfflineRunResult* result,
            RealtimeContext* realtime)
      : result_(result), realtime_(realtime) {
    const bool with_vio = config.mode == RunMode::kVil;  // the LiDAR side exists only in vil and lidar-only
    if (with_vio) {
      std::shared_ptr<const Vocabulary> vocabulary;
      if (config.loop.enabled) vocabulary = std::make_shared<const Vocabulary>(Vocabulary::load(
            config.vocabulary == "default" ? default_vocabulary_path() : config.vocabulary));
      loop_.emplace(config.loop, config.graph, vocabulary, calib, config.frontend, config.lidar.lidar, &imu_motion_);
    }
    lidar_.emplace(config.lidar, calib, with_vio ? &imu_poses_ : nullptr, with_vio ? &imu_motion_ : nullptr,
                   &result->lidar, loop_ ? &*loop_ : nullptr);
  }

  void handle(LidarMessage&& message) {
    if (auto* poses = std::get_if<PosesAdvanced>(&message)) {
      imu_poses_.insert(imu_poses_.end(), poses->imu_poses.begin(), poses->imu_poses.end());
      imu_motion_.insert(imu_motion_.end(), poses->imu_motion.begin(), poses->imu_motion.end());
      lidar_->poses_advanced();
    } else if (auto* frame = std::get_if<StereoFrame>(&message)) {
      if (loop_) loop_->stereo(*frame);
    } else {
      lidar_->scan(std::move(std::get<LidarScan>(message)));
    }
    if (realtime_) account_sweeps();
  }

  void finish() {
    lidar_->poses_advanced();
    if (realtime_) account_sweeps();
    result_->unmapped_scans = lidar_->unmapped_scans();
    if (loop_) result_->loop = loop_->finish();
  }

 private:
  // The sweeps mapped (or given up) since the last call: their poses' latencies, and the load they leave.
  void account_sweeps() {
    for (; latency_counted_ < result_->lidar.size(); ++latency_counted_) {
      realtime_->stats->lidar_pose_latency_ms.push_back(realtime_->clock.since_ms(result_->lidar[latency_counted_].t_ns));
    }
    const std::size_t done = result_->lidar.size() + lidar_->unmapped_scans() - lidar_->waiting_scans();
    realtime_->load.sweeps.done(done - sweeps_done_);
    sweeps_done_ = done;
  }

  OfflineRunResult* result_;
  RealtimeContext* realtime_;
  std::size_t latency_counted_ = 0;
  std::size_t sweeps_done_ = 0;
  Trajectory imu_poses_;
  Trajectory imu_motion_;
  std::optional<LoopClosureModule> loop_;
  std::optional<LidarFeeder> lidar_;
};

// The smoother (paper: the VIO thread). Frames wait (as frontend output) until the IMU stream has passed
// their time on the IMU clock, so a non-zero camera time offset never hands the VIO a frame too early.
// Passes stereo pairs, sweeps and its new IMU-rate poses on to the LiDAR side, if there is one.
class SmootherSide {
 public:
  SmootherSide(const RigCalibration& calib, const OfflineRunConfig& config, OfflineRunResult* result,
               Stage<LidarMessage>* lidar, RealtimeContext* realtime)
      : vio_(calib, config.vio), result_(result), lidar_(lidar), realtime_(realtime) {
    vio_.on_state([this](const VioStateOutput& s) {
      result_->camera_states.push_back({s.state.t_ns, s.state.T_W_I()});
      if (realtime_) {
        realtime_->stats->camera_state_latency_ms.push_back(realtime_->clock.since_ms(s.state.t_ns));
        realtime_->live.anchor(s.state);
      }
    });
    vio_.on_imu_pose([this](const VioImuOutput& p) {
      result_->imu_poses.push_back({p.t_ns, p.T_W_I});
      result_->imu_motion.push_back({p.t_ns, p.T_O_I});
    });
  }

  void handle(VioMessage&& message) {
    if (auto* sample = std::get_if<ImuSample>(&message)) {
      release_frames_before(sample->t_ns);
      vio_.add_imu(*sample);
      ++result_->imu_samples;
      if (lidar_) lidar_->push(new_poses());
    } else if (auto* tracked = std::get_if<TrackedFrame>(&message)) {
      if (lidar_) lidar_->push(std::move(tracked->frame));
      pending_.push_back(std::move(tracked->out));
    } else if (lidar_) {
      lidar_->push(std::move(std::get<LidarScan>(message)));
    }
  }

  void finish() {
    release_frames_before(std::numeric_limits<TimeNs>::max());
    if (lidar_) lidar_->push(new_poses());
  }

 private:
  void release_frames_before(TimeNs t_ns) {
    while (!pending_.empty() && pending_.front().t_ns < t_ns) {
      const auto start = std::chrono::steady_clock::now();
      vio_.add_frame(pending_.front());
      result_->smoother_ms.push_back(elapsed_ms(start));
      pending_.pop_front();
      if (realtime_) realtime_->load.frames.done();
    }
  }

  PosesAdvanced new_poses() {
    PosesAdvanced p;
    p.imu_poses.assign(result_->imu_poses.begin() + sent_, result_->imu_poses.end());
    p.imu_motion.assign(result_->imu_motion.begin() + sent_, result_->imu_motion.end());
    sent_ = result_->imu_poses.size();
    return p;
  }

  Vio vio_;
  OfflineRunResult* result_;
  Stage<LidarMessage>* lidar_;
  RealtimeContext* realtime_;
  std::deque<FrontendOutput> pending_;
  std::size_t sent_ = 0;
};

// The visual frontend (paper: the frontend thread): stereo pairs in, tracked features out; everything else
// passes through in order.
class FrontendSide {
 public:
  FrontendSide(const RigCalibration& calib, const OfflineRunConfig& config, OfflineRunResult* result,
               Stage<VioMessage>* vio)
      : frontend_(calib, config.frontend), cam_offset_ns_(calib.cam_time_offset_ns), result_(result), vio_(vio) {}

  void handle(FrontendMessage&& message) {
    if (auto* frame = std::get_if<StereoFrame>(&message)) {
      frame->t_ns += cam_offset_ns_;
      const auto start = std::chrono::steady_clock::now();
      FrontendOutput out = frontend_.process(*frame);
      result_->frontend_ms.push_back(elapsed_ms(start));
      result_->matches_per_frame.push_back(static_cast<int>(out.matches.size()));
      vio_->push(TrackedFrame{std::move(*frame), std::move(out)});
    } else if (auto* sample = std::get_if<ImuSample>(&message)) {
      vio_->push(*sample);
    } else {
      vio_->push(std::move(std::get<LidarScan>(message)));
    }
  }

 private:
  Frontend frontend_;
  TimeNs cam_offset_ns_;
  OfflineRunResult* result_;
  Stage<VioMessage>* vio_;
};

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

}  // namespace

std::string default_vocabulary_path() { return VILSLAM_DEFAULT_VOCABULARY; }

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
  const DatasetSummary& summary = reader.summary();
  OfflineRunResult result;
  RigCalibration calib = reader.calibration();
  if (config.time_offset.enabled && config.mode != RunMode::kLidarOnly) {
    result.time_offset = estimate_sequence_time_offset(reader, config.frontend, config.time_offset);
    if (result.time_offset) {
      calib.cam_time_offset_ns = s_to_ns(result.time_offset->offset_s);
      spdlog::info("camera-IMU time offset {:.2f} ms (t_imu = t_cam + offset) from {} intervals, residual {:.5f} "
                   "rad ({:.5f} at 0)",
                   1e3 * result.time_offset->offset_s, result.time_offset->intervals, result.time_offset->rms_rad,
                   result.time_offset->rms_zero_offset_rad);
    } else {
      spdlog::warn("camera-IMU time offset not observable in the first {} s (too little rotation or tracking); "
                   "keeping the calibration's {} ns",
                   config.time_offset.window_s, calib.cam_time_offset_ns);
    }
  }
  std::optional<RealtimeContext> realtime;
  if (config.realtime.speed > 0.0) {
    result.realtime.emplace();
    result.realtime->speed = config.realtime.speed;
    realtime.emplace(summary.start_t_ns, config, calib, &*result.realtime);
  }
  // Offline a full queue makes the reader wait. Live, the reader must not wait: the overload policy bounds the
  // pairs and sweeps, and the room left is for the IMU samples and pose updates between them (seconds of them).
  const std::size_t queue_capacity = realtime ? config.realtime.queue_capacity : kDefaultStageCapacity;
  // The modules, downstream first so that they outlive the upstream ones that feed them.
  const bool with_vio = config.mode != RunMode::kLidarOnly;
  std::optional<LidarSide> lidar_side;
  std::optional<Stage<LidarMessage>> lidar;
  if (config.mode != RunMode::kVio) {
    lidar_side.emplace(calib, config, &result, realtime ? &*realtime : nullptr);
    lidar.emplace([&](LidarMessage&& m) { lidar_side->handle(std::move(m)); }, config.threads, queue_capacity);
  }
  std::optional<SmootherSide> smoother_side;
  std::optional<Stage<VioMessage>> smoother;
  std::optional<FrontendSide> frontend_side;
  std::optional<Stage<FrontendMessage>> frontend;
  if (with_vio) {
    smoother_side.emplace(calib, config, &result, lidar ? &*lidar : nullptr, realtime ? &*realtime : nullptr);
    smoother.emplace([&](VioMessage&& m) { smoother_side->handle(std::move(m)); }, config.threads, queue_capacity);
    frontend_side.emplace(calib, config, &result, &*smoother);
    frontend.emplace([&](FrontendMessage&& m) { frontend_side->handle(std::move(m)); }, config.threads, queue_capacity);
  }
  const auto failed = [&] {
    return (frontend && frontend->failed()) || (smoother && smoother->failed()) || (lidar && lidar->failed());
  };

  // Real-time mode: the overload policy drops a stereo pair or a sweep when too many wait already.
  const auto push_sweep = [&](LidarScan&& scan) {
    if (realtime && lidar && !realtime->load.sweeps.admit()) return;
    if (frontend) frontend->push(std::move(scan));
    else if (lidar) lidar->push(std::move(scan));
  };
  // Real-time mode: a sweep is released at its end, when a live driver publishes it.
  std::deque<LidarScan> held_sweeps;
  const auto wait_until = [&](TimeNs t_ns) {
    result.realtime->max_release_lag_ms = std::max(result.realtime->max_release_lag_ms, realtime->clock.wait_until(t_ns));
  };
  const auto release_until = [&](TimeNs t_ns) {
    while (!held_sweeps.empty() && held_sweeps.front().end_t_ns() <= t_ns) {
      wait_until(held_sweeps.front().end_t_ns());
      push_sweep(std::move(held_sweeps.front()));
      held_sweeps.pop_front();
    }
    wait_until(t_ns);
  };

  reader.rewind();
  if (realtime) realtime->clock.restart();
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
    if (realtime) release_until(event->t_ns);
    bool last_frame_handed_over = false;
    std::visit(
        [&](auto& data) {
          using T = std::decay_t<decltype(data)>;
          if constexpr (std::is_same_v<T, ImuSample>) {
            last_frame_handed_over = frames_read >= summary.stereo_frames && data.t_ns > last_frame_t_ns;
            if (realtime && with_vio) {  // published before the sample goes down the pipeline
              if (const std::optional<SE3> T_W_I = realtime->live.add(data)) {
                result.realtime->live_imu_poses.push_back({data.t_ns, *T_W_I});
                result.realtime->imu_pose_latency_ms.push_back(realtime->clock.since_ms(data.t_ns));
              }
            }
            if (frontend) frontend->push(data);
          }
          if constexpr (std::is_same_v<T, StereoFrame>) {
            last_frame_t_ns = data.t_ns + calib.cam_time_offset_ns;
            ++frames_read;
            if (frontend && (!realtime || realtime->load.frames.admit())) frontend->push(std::move(data));
          }
          if constexpr (std::is_same_v<T, LidarScan>) {
            if (realtime && lidar) held_sweeps.push_back(std::move(data));
            else push_sweep(std::move(data));
          }
        },
        event->data);
    if ((with_vio && last_frame_handed_over) || failed()) break;
  }
  if (realtime && !failed()) release_until(held_sweeps.empty() ? last_t_ns : held_sweeps.back().end_t_ns());
  if (realtime) {
    result.realtime->dropped_frames = realtime->load.frames.dropped();
    result.realtime->dropped_sweeps = realtime->load.sweeps.dropped();
  }
  if (frontend) frontend->finish();
  if (smoother) {
    smoother->finish();
    smoother_side->finish();
  }
  if (lidar) {
    lidar->finish();
    lidar_side->finish();
  }
  result.data_s = first_t_ns ? ns_to_s(last_t_ns - *first_t_ns) : 0.0;
  result.run_wall_s = elapsed_ms(run_start) / 1e3;
  return result;
}

}  // namespace vilslam
