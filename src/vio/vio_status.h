#pragma once
// What the VIO went through at each camera-rate state (issue: "every module's status says what happened";
// written as vio_status.csv, docs/formats.md). A state is classified from what it was estimated with.
#include <string>

#include "common/time.h"
#include "vio/vio.h"

namespace vilslam {

enum class VioStatus {
  kTracking,      // the frame had enough stereo matches
  kFewMatches,    // fewer than few_matches: vision constrains the state weakly (blur, bare walls)
  kInertialOnly,  // no match at all (camera blacked out or covered): the IMU alone carried the state
  kImuGap,        // IMU samples were missing since the previous state: vision carried it (ImuGapModel)
  kLost,          // the VIO lost track at this frame (VioLossEvent): no state, the window starts again
  kRestarted,     // the first state of the window started again after a loss
};

struct VioStatusRecord {
  TimeNs t_ns = 0;
  VioStatus status = VioStatus::kTracking;
  int frame_matches = 0;
  int landmarks = 0;
  double imu_gap_s = 0;
  VioLoss loss = VioLoss::kNone;  // kLost: why
};

constexpr int kFewStereoMatches = 15;

// A restart first, then an IMU gap (the state lacked its inertial half), then the frame's matches.
VioStatusRecord vio_status(const VioStateOutput& state);
VioStatusRecord vio_status(const VioLossEvent& loss);
// "tracking", "few_matches", "inertial_only", "imu_gap", "restarted", or the loss's name ("lost_...").
std::string vio_status_name(const VioStatusRecord& record);

}  // namespace vilslam
