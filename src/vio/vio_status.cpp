#include "vio/vio_status.h"

namespace vilslam {

VioStatusRecord vio_status(const VioStateOutput& state) {
  VioStatusRecord r{state.state.t_ns, VioStatus::kTracking, state.frame_matches, state.landmarks, state.imu_gap_s};
  if (state.restarted) {
    r.status = VioStatus::kRestarted;
  } else if (state.imu_gap_s > 0) {
    r.status = VioStatus::kImuGap;
  } else if (state.frame_matches == 0) {
    r.status = VioStatus::kInertialOnly;
  } else if (state.frame_matches < kFewStereoMatches) {
    r.status = VioStatus::kFewMatches;
  }
  return r;
}

VioStatusRecord vio_status(const VioLossEvent& loss) {
  VioStatusRecord r{loss.t_ns, VioStatus::kLost, loss.frame_matches, loss.landmarks, 0.0};
  r.loss = loss.reason;
  return r;
}

std::string vio_status_name(const VioStatusRecord& record) {
  switch (record.status) {
    case VioStatus::kTracking: return "tracking";
    case VioStatus::kFewMatches: return "few_matches";
    case VioStatus::kInertialOnly: return "inertial_only";
    case VioStatus::kImuGap: return "imu_gap";
    case VioStatus::kLost: return vio_loss_name(record.loss);
    case VioStatus::kRestarted: return "restarted";
  }
  return {};
}

}  // namespace vilslam
