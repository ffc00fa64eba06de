#pragma once
// What LiDAR mapping went through at each sweep (written as lidar_status.csv, docs/formats.md): missing sweeps
// before it, a registration that did not converge, a pose far from the motion's prediction (the VIO prior
// or the constant-velocity model contradicted), a degenerate direction; or the sweep rejected
// (lidar/mapping_loss.h: the registration matched the wrong surfaces, matched almost nothing after a gap, or
// jumped far from the prediction).
#include <string>

#include "lidar/lidar_mapper.h"

namespace vilslam::lidar {

enum class MappingStatus {
  kOk,
  kReanchored,
  kDegenerate,
  kAfterGap,
  kNotConverged,
  kPredictionContradicted,
  kRejectedMismatched,
  kRejectedUnmatched,
  kRejectedJump
};

struct MappingStatusThresholds {
  double gap_s = 0.05;             // no sweep for longer (sweeps are contiguous; 20 Hz sensors turn in 0.05 s)
  double correction_m = 0.3;       // the registration moved the predicted pose farther (a VIO step is cm)
  double correction_deg = 3.0;
};

// The first that applies, in this order: rejected, reanchored, after a gap, not converged, prediction
// contradicted, degenerate.
MappingStatus mapping_status(const LidarMappingResult& sweep, const MappingStatusThresholds& thresholds = {});
std::string mapping_status_name(MappingStatus status);

}  // namespace vilslam::lidar
