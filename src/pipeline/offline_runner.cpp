#include "pipeline/offline_runner.h"

#include <chrono>
#include <deque>
#include <limits>
#include <optional>
#include <stdexcept>
#include <type_traits>

#include <spdlog/spdlog.h>

#include "common/error.h"
#include "frontend/frontend.h"
#include "pipeline/lidar_feeder.h"
#include "pipeline/time_offset_pass.h"

namespace vilslam {
namespace {

double elapsed_ms(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

// Feeds the VIO and times it. Frames wait (as frontend output) until the IMU stream has passed their
// time on the IMU clock, so a non-zero camera time offset never hands the VIO a frame too early.
class VioFeeder {
 public:
  VioFeeder(const RigCalibration& calib, const OfflineRunConfig& config, OfflineRunResult* result)
      : frontend_(calib, config.frontend), vio_(calib, config.vio), result_(result),
        cam_offset_ns_(calib.cam_time_offset_ns) {
    vio_.on_state([this](const VioStateOutput& s) { result_->camera_states.push_back({s.state.t_ns, s.state.T_W_I()}); });
    vio_.on_imu_pose([this](const VioImuOutput& p) {
      result_->imu_poses.push_back({p.t_ns, p.T_W_I});
      result_->imu_motion.push_back({p.t_ns, p.T_O_I});
    });
  }

  void imu(const ImuSample& sample) {
    release_frames_before(sample.t_ns);
    vio_.add_imu(sample);
    ++result_->imu_samples;
  }

  void stereo(StereoFrame frame) {
    frame.t_ns += cam_offset_ns_;
    const auto start = std::chrono::steady_clock::now();
    FrontendOutput out = frontend_.process(frame);
    result_->frontend_ms.push_back(elapsed_ms(start));
    result_->matches_per_frame.push_back(static_cast<int>(out.matches.size()));
    pending_.push_back(std::move(out));
  }

  bool idle() const { return pending_.empty(); }
  void finish() { release_frames_before(std::numeric_limits<TimeNs>::max()); }

 private:
  void release_frames_before(TimeNs t_ns) {
    while (!pending_.empty() && pending_.front().t_ns < t_ns) {
      const auto start = std::chrono::steady_clock::now();
      vio_.add_frame(pending_.front());
      result_->smoother_ms.push_back(elapsed_ms(start));
      pending_.pop_front();
    }
  }

  Frontend frontend_;
  Vio vio_;
  OfflineRunResult* result_;
  TimeNs cam_offset_ns_;
  std::deque<FrontendOutput> pending_;
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
  std::optional<VioFeeder> vio;
  if (config.mode != RunMode::kLidarOnly) vio.emplace(calib, config, &result);
  std::optional<LoopClosureModule> loop;
  if (config.mode == RunMode::kVil) {
    std::shared_ptr<const Vocabulary> vocabulary;
    if (config.loop.enabled) vocabulary = std::make_shared<const Vocabulary>(Vocabulary::load(
          config.vocabulary == "default" ? default_vocabulary_path() : config.vocabulary));
    loop.emplace(config.loop, config.graph, vocabulary, calib, config.frontend, config.lidar.lidar,
                 &result.imu_motion);
  }
  std::optional<LidarFeeder> lidar;
  if (config.mode != RunMode::kVio) {
    lidar.emplace(config.lidar, calib, vio ? &result.imu_poses : nullptr,
                  vio ? &result.imu_motion : nullptr, &result.lidar,
                  loop ? &*loop : nullptr);
  }
  const TimeNs cam_offset_ns = calib.cam_time_offset_ns;
  reader.rewind();
  // The IMU stream may run on long after the last image (EuRoC slices): stop once every frame is in.
  const auto all_frames_in = [&] { return vio && result.matches_per_frame.size() >= summary.stereo_frames && vio->idle(); };
  const double span_ns = std::max<double>(1.0, double(summary.end_t_ns - summary.start_t_ns));
  while (auto event = reader.next()) {
    if (progress) progress(double(event->t_ns - summary.start_t_ns) / span_ns);
    std::visit(
        [&](auto& data) {
          using T = std::decay_t<decltype(data)>;
          if constexpr (std::is_same_v<T, ImuSample>) {
            if (vio) vio->imu(data);
            if (vio && lidar) lidar->poses_advanced();
          }
          if constexpr (std::is_same_v<T, StereoFrame>) {
            if (loop) {
              StereoFrame on_imu_clock = data;  // shares the images
              on_imu_clock.t_ns += cam_offset_ns;
              loop->stereo(on_imu_clock);
            }
            if (vio) vio->stereo(std::move(data));
          }
          if constexpr (std::is_same_v<T, LidarScan>) {
            if (lidar) lidar->scan(std::move(data));
          }
        },
        event->data);
    if (all_frames_in()) break;
  }
  if (vio) vio->finish();
  if (lidar) {
    lidar->poses_advanced();
    result.unmapped_scans = lidar->unmapped_scans();
  }
  if (loop) result.loop = loop->finish();
  return result;
}

}  // namespace vilslam
