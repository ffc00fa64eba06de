#pragma once
// Deterministic offline mode (paper, system overview): the dataset is read as one time-ordered event
// stream and pushed into the System (pipeline/system.h) in that order: IMU samples go to the VIO, stereo
// pairs through the visual frontend into the VIO, LiDAR sweeps to the mapper with the VIO's IMU-rate poses
// as motion prior (vil) or without it (lidar-only). Each module sees the stream in the dataset's order, so
// running them on threads of their own changes nothing but the time the run takes. With
// config.realtime.speed > 0 the events are released on the wall clock instead (pipeline/realtime.h).
#include <functional>

#include "io/dataset.h"
#include "pipeline/run_types.h"

namespace vilslam {

// Runs the whole sequence. Throws InputError for bad input, including a mode the dataset cannot serve
// (the VIO needs cameras and an IMU, which the KITTI layout lacks; the LiDAR modes need scans).
// progress (optional) receives the share of the sequence's time span read so far, in [0, 1].
OfflineRunResult run_offline(DatasetReader& reader, const OfflineRunConfig& config,
                             const std::function<void(double)>& progress = {});

}  // namespace vilslam
