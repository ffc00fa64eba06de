#pragma once
// The camera-IMU time offset of a sequence, estimated before the run (`time_offset.enabled` in the run
// config, docs/pipeline.md): the frontend tracks the stereo pairs of the first time_offset.window_s and
// its frame-to-frame PnP motions give the camera's rotations, which vio/time_offset.h matches against the
// gyro. Only the dataset's own streams and the calibration's rotation R_I_C0 are used.
#include <optional>

#include "frontend/frontend_config.h"
#include "io/dataset.h"
#include "vio/time_offset.h"

namespace vilslam {

// Reads the reader from its start (rewinds it before and after). nullopt when the window has too few
// tracked intervals or too little rotation to observe the offset.
std::optional<TimeOffsetEstimate> estimate_sequence_time_offset(DatasetReader& reader, const FrontendConfig& frontend,
                                                                const TimeOffsetConfig& config);

}  // namespace vilslam
