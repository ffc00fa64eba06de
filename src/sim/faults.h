#pragma once
// Sensor faults injected by the simulator: blackouts, dropouts, gaps and exposure jumps (clock offsets
// are calibration errors, sim/calibration_errors.h). They are not
// recorded in the dataset's calibration: the system under test has to cope with them.
#include <vector>

#include "common/time.h"

namespace vilslam::sim {

// [begin_s, end_s) in seconds since the start of the sequence.
struct FaultInterval {
  double begin_s = 0;
  double end_s = 0;
};

struct FaultConfig {
  std::vector<FaultInterval> camera_blackouts;  // images are black (lens covered, lights out)
  std::vector<FaultInterval> lidar_dropouts;    // sweeps starting in the interval are missing
  std::vector<FaultInterval> imu_gaps;          // samples in the interval are missing
  // Sudden exposure changes (a door to daylight, an auto-exposure overshoot): inside the interval the image
  // brightness jumps to exposure_jump_gain times the usual, and back at its end.
  std::vector<FaultInterval> exposure_jumps;
  double exposure_jump_gain = 2.5;
};

// True when t_ns (relative to the sequence start) falls in one of the intervals.
bool in_fault(const std::vector<FaultInterval>& intervals, TimeNs since_start_ns);

}  // namespace vilslam::sim
