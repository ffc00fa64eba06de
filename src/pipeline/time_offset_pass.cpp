#include "pipeline/time_offset_pass.h"

#include <type_traits>
#include <variant>

#include "frontend/frontend.h"

namespace vilslam {

std::optional<TimeOffsetEstimate> estimate_sequence_time_offset(DatasetReader& reader, const FrontendConfig& frontend,
                                                                const TimeOffsetConfig& config) {
  const RigCalibration& calib = reader.calibration();
  Frontend tracker(calib, frontend);
  std::vector<ImuSample> imu;
  std::vector<CameraRotation> rotations;
  std::optional<TimeNs> first_frame_ns, previous_frame_ns;
  const TimeNs window_ns = s_to_ns(config.window_s), margin_ns = s_to_ns(config.max_abs_offset_s);
  reader.rewind();
  while (auto event = reader.next()) {
    if (first_frame_ns && event->t_ns > *first_frame_ns + window_ns + margin_ns) break;
    std::visit(
        [&](auto& data) {
          using T = std::decay_t<decltype(data)>;
          if constexpr (std::is_same_v<T, ImuSample>) imu.push_back(data);
          if constexpr (std::is_same_v<T, StereoFrame>) {
            if (first_frame_ns && data.t_ns > *first_frame_ns + window_ns) return;
            if (!first_frame_ns) first_frame_ns = data.t_ns;
            tracker.process(data);
            const FrontendStats& stats = tracker.last_stats();
            if (stats.motion_valid && previous_frame_ns)
              rotations.push_back({*previous_frame_ns, data.t_ns, stats.T_C0cur_C0prev.rotation().transpose()});
            previous_frame_ns = data.t_ns;
          }
        },
        event->data);
  }
  reader.rewind();
  return estimate_cam_time_offset(rotations, imu, calib.T_I_C0.rotation(), config);
}

}  // namespace vilslam
