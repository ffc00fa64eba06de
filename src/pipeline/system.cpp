#include "pipeline/system.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <deque>
#include <limits>
#include <mutex>
#include <optional>
#include <utility>
#include <variant>

#include <spdlog/spdlog.h>

#include "common/error.h"
#include "frontend/frontend.h"
#include "loop/map_file.h"
#include "pipeline/lidar_feeder.h"
#include "pipeline/live_propagator.h"
#include "pipeline/online_time_offset.h"
#include "pipeline/run_segments.h"
#include "pipeline/stage.h"

namespace vilslam {
namespace {

double elapsed_ms(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

// What the LiDAR side receives, in push order: stereo pairs (key images, on the IMU clock), sweeps, and
// after each IMU sample the IMU-rate poses the VIO published for it (none before initialization).
struct PosesAdvanced {
  Trajectory imu_poses;   // T_W_I
  Trajectory imu_motion;  // T_O_I at the same samples
  std::vector<double> tilt_sigma_rad;  // VioImuOutput::tilt_sigma_rad at the same samples
};
// The VIO lost track after the poses sent so far (vio/vio.h VioLossEvent).
struct VioLost {};
using LidarMessage = std::variant<PosesAdvanced, VioLost, StereoFrame, LidarScan>;

// A stereo pair on the IMU clock with its frontend output.
struct TrackedFrame {
  StereoFrame frame;
  FrontendOutput out;
};
using VioMessage = std::variant<ImuSample, TrackedFrame, LidarScan>;
using FrontendMessage = std::variant<ImuSample, StereoFrame, LidarScan>;

// What the modules share besides their messages: the callbacks, the live propagator (when the IMU-rate pose
// is wanted) and the overload policy's load (real-time mode only).
struct Shared {
  SystemCallbacks callbacks;
  std::atomic<bool> lidar_lost{false};
  std::optional<LivePropagator> live;
  std::optional<PipelineLoad> load;
};

// LiDAR mapping and loop closure (paper: the LiDAR mapping and loop closure threads). Keeps its own copy of
// the VIO's IMU-rate poses, grown exactly as the VIO published them, so it never reads the VIO's memory.
class LidarSide {
 public:
  LidarSide(const RigCalibration& calib, const OfflineRunConfig& config, std::optional<loop::SavedMap> map,
            OfflineRunResult* result, Shared* shared)
      : result_(result), shared_(shared) {
    const bool with_vio = config.mode == RunMode::kVil;  // the LiDAR side exists only in vil and lidar-only
    if (with_vio) {
      std::shared_ptr<const Vocabulary> vocabulary;
      if (config.loop.enabled) {
        vocabulary = std::make_shared<const Vocabulary>(Vocabulary::load(vocabulary_file(config.vocabulary)));
      }
      loop_.emplace(config.loop, config.graph, vocabulary, calib, config.frontend, config.lidar.lidar, &imu_motion_);
      if (map) {
        loop_->load_map(std::move(*map), true);
      } else if (!config.load_map.empty()) {
        loop_->load_map(load_checked_map(config.load_map, loop::vocabulary_identity(vocabulary_file(config.vocabulary)), calib));
      }
    }
    lidar_.emplace(config.lidar, calib, with_vio ? &imu_poses_ : nullptr, with_vio ? &imu_motion_ : nullptr,
                   with_vio ? &imu_tilt_sigma_rad_ : nullptr, &result->lidar, &result->lidar_rejected,
                   loop_ ? &*loop_ : nullptr, !resets_on_lidar_lost(config));
  }

  void handle(LidarMessage&& message) {
    if (auto* poses = std::get_if<PosesAdvanced>(&message)) {
      imu_poses_.insert(imu_poses_.end(), poses->imu_poses.begin(), poses->imu_poses.end());
      imu_motion_.insert(imu_motion_.end(), poses->imu_motion.begin(), poses->imu_motion.end());
      imu_tilt_sigma_rad_.insert(imu_tilt_sigma_rad_.end(), poses->tilt_sigma_rad.begin(), poses->tilt_sigma_rad.end());
      lidar_->poses_advanced();
    } else if (std::holds_alternative<VioLost>(message)) {
      lidar_->vio_lost();
    } else if (auto* frame = std::get_if<StereoFrame>(&message)) {
      if (loop_) loop_->stereo(*frame);
    } else {
      lidar_->scan(std::move(std::get<LidarScan>(message)));
    }
    publish();
    note_lost();
  }

  void finish() {
    lidar_->finish();
    publish();
    note_lost();
    result_->unmapped_scans = lidar_->unmapped_scans();
    result_->lidar_sensor = lidar_->sensor_report();
    if (loop_) result_->loop = loop_->finish();
  }

 private:
  void note_lost() {
    if (!lidar_->lost_t_ns() || !result_->lidar_lost_t_ns.empty()) return;
    result_->lidar_lost_t_ns.push_back(*lidar_->lost_t_ns());
    spdlog::warn("LiDAR mapping lost at t_ns={}: its last sweeps were rejected (the motion prior no longer places "
                 "them on the map; lidar_status.csv); no LiDAR poses after it until a reset",
                 *lidar_->lost_t_ns());
    shared_->lidar_lost = true;
  }

  // What was mapped (or given up) since the last call: its outputs, and the load it leaves.
  void publish() {
    const SystemCallbacks& cb = shared_->callbacks;
    if (cb.lidar_features && sweeps_published_ < result_->lidar.size()) {
      const lidar::LidarMappingResult& newest = result_->lidar.back();
      cb.lidar_features({newest.t_ns, newest.T_W_L}, lidar_->last_features());
    }
    for (; sweeps_published_ < result_->lidar.size(); ++sweeps_published_) {
      if (cb.lidar_pose) cb.lidar_pose(result_->lidar[sweeps_published_]);
    }
    if (loop_) {
      for (; global_published_ < loop_->lidar_global().size(); ++global_published_) {
        if (cb.lidar_global_pose) cb.lidar_global_pose(loop_->lidar_global()[global_published_]);
      }
      for (; candidates_published_ < loop_->candidates().size(); ++candidates_published_) {
        if (cb.loop_candidate) cb.loop_candidate(loop_->candidates()[candidates_published_]);
      }
    }
    if (shared_->load) {
      const std::size_t done = result_->lidar.size() + result_->lidar_rejected.size() + lidar_->unmapped_scans() -
                               lidar_->waiting_scans();
      shared_->load->sweeps.done(done - sweeps_done_);
      sweeps_done_ = done;
    }
  }

  OfflineRunResult* result_;
  Shared* shared_;
  std::size_t sweeps_published_ = 0;
  std::size_t global_published_ = 0;
  std::size_t candidates_published_ = 0;
  std::size_t sweeps_done_ = 0;
  Trajectory imu_poses_;
  Trajectory imu_motion_;
  std::vector<double> imu_tilt_sigma_rad_;
  std::optional<LoopClosureModule> loop_;
  std::optional<LidarFeeder> lidar_;
};

// The smoother (paper: the VIO thread). Frames wait (as frontend output) until the IMU stream has passed
// their time on the IMU clock, so a non-zero camera time offset never hands the VIO a frame too early.
// Passes stereo pairs, sweeps and its new IMU-rate poses on to the LiDAR side, if there is one.
class SmootherSide {
 public:
  SmootherSide(const RigCalibration& calib, const OfflineRunConfig& config, OfflineRunResult* result,
               Stage<LidarMessage>* lidar, Shared* shared)
      : vio_(calib, config.vio), max_imu_step_ns_(s_to_ns(config.vio.imu_gap.max_step_s)), result_(result),
        lidar_(lidar), shared_(shared) {
    vio_.on_state([this](const VioStateOutput& s) {
      result_->camera_states.push_back({s.state.t_ns, s.state.T_W_I()});
      result_->vio_status.push_back(vio_status(s));
      if (shared_->callbacks.vio_status) shared_->callbacks.vio_status(result_->vio_status.back());
      if (shared_->callbacks.camera_state) shared_->callbacks.camera_state(result_->camera_states.back());
      if (shared_->live) shared_->live->anchor(s.state);
    });
    vio_.on_lost([this](const VioLossEvent& e) {
      result_->vio_status.push_back(vio_status(e));
      if (shared_->callbacks.vio_status) shared_->callbacks.vio_status(result_->vio_status.back());
      if (shared_->live) shared_->live->lost();
      if (lidar_) {
        lidar_->push(new_poses());
        lidar_->push(VioLost{});
      }
    });
    vio_.on_imu_pose([this](const VioImuOutput& p) {
      result_->imu_poses.push_back({p.t_ns, p.T_W_I});
      result_->imu_motion.push_back({p.t_ns, p.T_O_I});
      unsent_tilt_sigma_rad_.push_back(p.tilt_sigma_rad);
    });
  }

  void handle(VioMessage&& message) {
    if (auto* sample = std::get_if<ImuSample>(&message)) {
      // After an IMU gap the sample goes in first: the frames it releases then interpolate across the gap (their
      // IMU factors carry ImuGapModel's noise) instead of holding the last sample before it.
      const bool after_gap = last_imu_t_ns_ && sample->t_ns - *last_imu_t_ns_ > max_imu_step_ns_;
      last_imu_t_ns_ = sample->t_ns;
      if (after_gap) vio_.add_imu(*sample);
      release_frames_before(sample->t_ns);
      if (!after_gap) vio_.add_imu(*sample);
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
      if (shared_->load) shared_->load->frames.done();
    }
  }

  PosesAdvanced new_poses() {
    PosesAdvanced p;
    p.imu_poses.assign(result_->imu_poses.begin() + sent_, result_->imu_poses.end());
    p.imu_motion.assign(result_->imu_motion.begin() + sent_, result_->imu_motion.end());
    p.tilt_sigma_rad.swap(unsent_tilt_sigma_rad_);
    sent_ = result_->imu_poses.size();
    return p;
  }

  Vio vio_;
  TimeNs max_imu_step_ns_;
  std::optional<TimeNs> last_imu_t_ns_;
  OfflineRunResult* result_;
  Stage<LidarMessage>* lidar_;
  Shared* shared_;
  std::deque<FrontendOutput> pending_;
  std::size_t sent_ = 0;
  std::vector<double> unsent_tilt_sigma_rad_;  // of the IMU-rate poses from sent_ on
};

// The visual frontend (paper: the frontend thread): stereo pairs in, tracked features out; everything else
// passes through in order.
class FrontendSide {
 public:
  FrontendSide(const RigCalibration& calib, const OfflineRunConfig& config, OfflineRunResult* result,
               Stage<VioMessage>* vio)
      : frontend_(calib, config.frontend), cam_offset_ns_(calib.cam_time_offset_ns), result_(result), vio_(vio) {
    if (config.time_offset.online) online_offset_.emplace(config.time_offset, calib.T_I_C0.rotation());
  }

  void handle(FrontendMessage&& message) {
    if (auto* frame = std::get_if<StereoFrame>(&message)) {
      const TimeNs t_cam_ns = frame->t_ns;
      frame->t_ns += cam_offset_ns_;
      const auto start = std::chrono::steady_clock::now();
      FrontendOutput out = frontend_.process(*frame);
      result_->frontend_ms.push_back(elapsed_ms(start));
      result_->matches_per_frame.push_back(static_cast<int>(out.matches.size()));
      if (online_offset_) update_offset(t_cam_ns, frame->t_ns);
      if (frontend_.last_stats().vignetting_fitted) log_vignetting(t_cam_ns);
      if (frontend_.last_stats().vignetting_rejected) {
        spdlog::warn("vignetting self-calibration stopped at t_ns={}: no plausible fit (the tracks do not constrain it, "
                     "or it leaves an edge darker than {} or brighter than {} times the centre: a scene that is not "
                     "static?); the images keep the correction before it",
                     t_cam_ns, StereoDevignetting::kMinAttenuation, StereoDevignetting::kMaxAttenuation);
      }
      vio_->push(TrackedFrame{std::move(*frame), std::move(out)});
    } else if (auto* sample = std::get_if<ImuSample>(&message)) {
      if (online_offset_) online_offset_->add_imu(*sample);
      vio_->push(*sample);
    } else {
      vio_->push(std::move(std::get<LidarScan>(message)));
    }
  }

 private:
  // The fitted falloff, as the brightness left in the image's corner (frontend/vignetting.h).
  void log_vignetting(TimeNs t_cam_ns) const {
    for (int camera = 0; camera < 2; ++camera) {
      const VignettingModel& m = *frontend_.vignetting(camera);
      spdlog::info("camera {} vignetting fitted at t_ns={}: pixel (0, 0) at {:.3f} of the centre's brightness "
                   "(k = {:.4f} {:.4f} {:.4f})",
                   camera, t_cam_ns, m.attenuation(0, 0), m.k.x(), m.k.y(), m.k.z());
    }
  }

  // time_offset.online: the frame's rotation goes to the estimator, and a new estimate moves the frames after it.
  void update_offset(TimeNs t_cam_ns, TimeNs t_imu_ns) {
    const FrontendStats& stats = frontend_.last_stats();
    const std::optional<TimeNs> previous_ns = std::exchange(previous_t_cam_ns_, t_cam_ns);
    if (!previous_ns || !stats.motion_valid) return;
    const std::optional<TimeOffsetEstimate> e =
        online_offset_->add_rotation({*previous_ns, t_cam_ns, stats.T_C0cur_C0prev.rotation().transpose()});
    if (!e) return;
    const TimeNs max_change_ns = (t_cam_ns - *previous_ns) / 4;
    cam_offset_ns_ = std::clamp(s_to_ns(e->offset_s), cam_offset_ns_ - max_change_ns, cam_offset_ns_ + max_change_ns);
    result_->time_offset_online.push_back({t_imu_ns, *e, ns_to_s(cam_offset_ns_)});
  }

  Frontend frontend_;
  TimeNs cam_offset_ns_;
  OfflineRunResult* result_;
  Stage<VioMessage>* vio_;
  std::optional<OnlineTimeOffsetEstimator> online_offset_;
  std::optional<TimeNs> previous_t_cam_ns_;
};

}  // namespace

struct System::Impl {
  Impl(const RigCalibration& calib, const OfflineRunConfig& config, SystemCallbacks callbacks,
       std::optional<loop::SavedMap> map) {
    const bool with_vio = config.mode != RunMode::kLidarOnly;
    if (config.mode != RunMode::kVio && !calib.has_lidar) {
      throw InputError("rig calibration", "mode " + run_mode_name(config.mode) + " needs a LiDAR calibration");
    }
    if ((map || !config.load_map.empty()) && (config.mode != RunMode::kVil || !config.loop.enabled)) {
      throw InputError(map ? "map" : config.load_map, "a map is re-localized in by mode vil with loop closure enabled");
    }
    shared.callbacks = std::move(callbacks);
    if (with_vio && shared.callbacks.imu_pose) {
      shared.live.emplace(calib.imu, Vec3(0, 0, -config.vio.smoother.gravity_m_s2));
    }
    if (config.realtime.speed > 0.0) shared.load.emplace(config.realtime);
    // Offline a full queue makes the pusher wait. Live, it must not wait: the overload policy bounds the pairs
    // and sweeps, and the room left is for the IMU samples and pose updates between them (seconds of them).
    const std::size_t capacity = shared.load ? config.realtime.queue_capacity : kDefaultStageCapacity;
    // The modules, downstream first so that they outlive the upstream ones that feed them.
    if (config.mode != RunMode::kVio) {
      lidar_side.emplace(calib, config, std::move(map), &result, &shared);
      lidar.emplace([this](LidarMessage&& m) { lidar_side->handle(std::move(m)); }, config.threads, capacity);
    }
    if (with_vio) {
      smoother_side.emplace(calib, config, &result, lidar ? &*lidar : nullptr, &shared);
      smoother.emplace([this](VioMessage&& m) { smoother_side->handle(std::move(m)); }, config.threads, capacity);
      frontend_side.emplace(calib, config, &result, &*smoother);
      frontend.emplace([this](FrontendMessage&& m) { frontend_side->handle(std::move(m)); }, config.threads, capacity);
    }
  }

  OfflineRunResult result;
  Shared shared;
  std::mutex push_mutex;  // one push at a time: the modules see one order
  std::optional<LidarSide> lidar_side;
  std::optional<Stage<LidarMessage>> lidar;
  std::optional<SmootherSide> smoother_side;
  std::optional<Stage<VioMessage>> smoother;
  std::optional<FrontendSide> frontend_side;
  std::optional<Stage<FrontendMessage>> frontend;
};

System::System(const RigCalibration& calib, const OfflineRunConfig& config, SystemCallbacks callbacks,
               std::optional<loop::SavedMap> map)
    : impl_(std::make_unique<Impl>(calib, config, std::move(callbacks), std::move(map))) {}

System::~System() = default;

void System::push_imu(const ImuSample& sample) {
  std::lock_guard<std::mutex> lock(impl_->push_mutex);
  Shared& shared = impl_->shared;
  if (shared.live) {  // published before the sample goes down the pipeline
    if (const std::optional<SE3> T_W_I = shared.live->add(sample)) shared.callbacks.imu_pose({sample.t_ns, *T_W_I});
  }
  if (impl_->frontend) impl_->frontend->push(sample);
}

bool System::push_stereo(StereoFrame frame) {
  std::lock_guard<std::mutex> lock(impl_->push_mutex);
  if (!impl_->frontend) return true;  // lidar-only: no use for images
  if (impl_->shared.load && !impl_->shared.load->frames.admit()) return false;
  impl_->frontend->push(std::move(frame));
  return true;
}

bool System::push_scan(LidarScan scan) {
  std::lock_guard<std::mutex> lock(impl_->push_mutex);
  if (!impl_->lidar) return true;  // vio: no use for sweeps
  if (impl_->shared.load && !impl_->shared.load->sweeps.admit()) return false;
  if (impl_->frontend) impl_->frontend->push(std::move(scan));  // in order with the IMU samples and pairs
  else impl_->lidar->push(std::move(scan));
  return true;
}

bool System::failed() const {
  return (impl_->frontend && impl_->frontend->failed()) || (impl_->smoother && impl_->smoother->failed()) ||
         (impl_->lidar && impl_->lidar->failed());
}

bool System::lidar_lost() const { return impl_->shared.lidar_lost; }

void System::wait_idle() {
  // Upstream first: once a module is idle, nothing more reaches the next one until the next push.
  if (impl_->frontend) impl_->frontend->wait_idle();
  if (impl_->smoother) impl_->smoother->wait_idle();
  if (impl_->lidar) impl_->lidar->wait_idle();
}

std::size_t System::dropped_frames() const { return impl_->shared.load ? impl_->shared.load->frames.dropped() : 0; }
std::size_t System::dropped_sweeps() const { return impl_->shared.load ? impl_->shared.load->sweeps.dropped() : 0; }

QueueDepths System::max_queue_depths() const {
  QueueDepths d;
  if (impl_->frontend) d.frontend = impl_->frontend->max_depth();
  if (impl_->smoother) d.smoother = impl_->smoother->max_depth();
  if (impl_->lidar) d.lidar = impl_->lidar->max_depth();
  return d;
}

OfflineRunResult System::finish() {
  Impl& m = *impl_;
  if (m.frontend) m.frontend->finish();
  if (m.smoother) {
    m.smoother->finish();
    m.smoother_side->finish();
  }
  if (m.lidar) {
    m.lidar->finish();
    m.lidar_side->finish();
  }
  return std::move(m.result);
}

}  // namespace vilslam
