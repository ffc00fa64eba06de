#include "pipeline/offline_runner.h"

#include <chrono>
#include <deque>
#include <limits>
#include <type_traits>

#include "common/error.h"
#include "frontend/frontend.h"

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
    vio_.on_imu_pose([this](const VioImuOutput& p) { result_->imu_poses.push_back({p.t_ns, p.T_W_I}); });
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

}  // namespace

OfflineRunResult run_offline(DatasetReader& reader, const OfflineRunConfig& config) {
  const DatasetSummary& summary = reader.summary();
  if (summary.stereo_frames == 0 || summary.imu_samples == 0) {
    throw InputError(summary.path, "the VIO needs stereo images and IMU samples (" + summary.format +
                                       " dataset has " + std::to_string(summary.stereo_frames) + " frames, " +
                                       std::to_string(summary.imu_samples) + " IMU samples)");
  }
  OfflineRunResult result;
  VioFeeder feeder(reader.calibration(), config, &result);
  reader.rewind();
  // The IMU stream may run on long after the last image (EuRoC slices): stop once every frame is in.
  const auto all_frames_in = [&] { return result.matches_per_frame.size() >= summary.stereo_frames && feeder.idle(); };
  while (auto event = reader.next()) {
    std::visit(
        [&](auto& data) {
          using T = std::decay_t<decltype(data)>;
          if constexpr (std::is_same_v<T, ImuSample>) feeder.imu(data);
          if constexpr (std::is_same_v<T, StereoFrame>) feeder.stereo(std::move(data));
        },
        event->data);
    if (all_frames_in()) break;
  }
  feeder.finish();
  return result;
}

}  // namespace vilslam
