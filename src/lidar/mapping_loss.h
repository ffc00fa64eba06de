#pragma once
// When LiDAR mapping cannot place a sweep, and when it is lost (docs/lidar.md, "Losing the map"). A sweep is
// rejected when its registration matched mostly the wrong surfaces, when it came after a gap (its prediction
// spans an outage) and matched almost nothing, or when it moved its predicted pose far more than any working
// prior is off. Either way the pose is not the sweep's and the sweep must not enter the map: after an outage of
// the whole rig (drivers restarting while the robot moves) a sweep inserted where the prior put it starts a
// second, displaced copy of the world, which the next sweeps then register on without a complaint. One rejected
// sweep is skipped (a glitch); the mapper is lost after several in a row (its prediction itself is wrong).
#include <string>

namespace vilslam::lidar {

enum class MappingLoss { kNone, kMismatched, kUnmatched, kJump };

// What a registered sweep's rejection is decided on (lidar_mapper.h LidarMappingResult).
struct SweepFit {
  double matched_fraction = 0.0;  // features that found a line or plane
  double inlier_fraction = 0.0;   // of those, the ones within the loss scale of it
  double gap_s = 0.0;             // since the last sweep the mapper kept
  double correction_m = 0.0;      // how far the registration moved the prediction
  double correction_deg = 0.0;
  // The prediction came from a working motion prior (the VIO's poses). Without one (LiDAR-only, a VIO outage) it
  // is a constant-velocity guess, which a turn from rest or a jolt misses by far more than a sweep's registration
  // error: the realistic outdoor route's LiDAR-only run corrects it by up to 15 deg and 1.45 m (75 of 1,380 sweeps
  // above 10 deg) and still maps the route (docs/lidar.md, "Losing the map"). Only a prior-aided sweep can be a jump.
  bool prior_aided = true;
};

// Thresholds from the registrations of 245 runs of every simulated route and sensor (docs/lidar.md, "Losing the
// map"): their inlier fractions were all at least 0.42, their matched fractions at least 0.37 with spinning
// LiDARs (a non-repetitive sensor facing new space matched 0.01), their corrections within 0.2 m and 1.5 deg
// with the default configs (5.6 deg in a trial).
struct MappingLossConfig {
  bool enabled = true;
  double min_inlier_fraction = 0.35;
  double min_matched_fraction = 0.25;  // applies after a gap only: a sweep may look at new space
  double gap_s = 0.15;                 // more than a sweep missing
  double max_correction_m = 1.0;
  double max_correction_deg = 10.0;
  int lost_after_rejected = 3;  // consecutive rejected sweeps
};

// Why a registered sweep is rejected, in this order: mismatched, unmatched, jump (prior-aided sweeps only). kNone
// when it is kept or the check is off.
MappingLoss mapping_loss(const SweepFit& fit, const MappingLossConfig& config);

// Throws InputError naming source for thresholds out of range.
void validate_mapping_loss_config(const MappingLossConfig& config, const std::string& source);

}  // namespace vilslam::lidar
