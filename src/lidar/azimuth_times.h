#pragma once
// Per-point times of a spinning sweep that came without them (a KITTI .bin, a PCD or PointCloud2 with no time
// field): each point is given the instant the sensor head swept its azimuth, as LOAM and FAST-LIO do, so that
// dewarping can still move it. Applied by the pipeline and the dense map when they dewarp (docs/lidar.md,
// "Per-point time").
#include "common/types.h"
#include "lidar/sensor_traits.h"

namespace vilslam::lidar {

// True when some point carries a time offset other than 0 (the source gave per-point times).
bool has_point_times(const LidarScan& scan);

// Sets each point's t_offset_s to the share of the turn from the sweep's start azimuth to its own, times
// sweep_period_s. The start is the azimuth of the first point in the file (of its ring, with a ring field:
// drivers may list the points ring by ring); the spin direction is the majority sign of the small azimuth
// steps between consecutive points of a ring (clockwise seen from above, as Velodyne, Ouster and Hesai
// heads turn, when there are none). Within 5 degrees of the start the file order tells whether a point
// opens or closes the sweep. Needs sweep_period_s > 0.
void assign_azimuth_times(LidarScan& scan, double sweep_period_s);

// Whether a spinning head's sweeps without per-point times need the azimuth times at all: drivers and datasets
// also hand out sweeps deskewed already (the real BALM sequence: with azimuth times dewarped by the registered
// motion its sweeps fit their map at 11 cm rms, as given at 6.5 cm). Each moving sweep votes for the hypothesis
// whose registration fits better; after kVotes votes the majority decides, for the rest of the run.
class AzimuthClockVote {
 public:
  enum class State { kUndecided, kTimed, kInstant };
  void vote(double rms_timed_m, double rms_instant_m);
  State state() const { return state_; }

  static constexpr int kVotes = 5;

 private:
  int votes_ = 0;
  int timed_better_ = 0;
  State state_ = State::kUndecided;
};

// The rule of the pipeline and the dense map: a sweep without per-point times from a spinning LiDAR (its traits,
// read off the data: lidar/sensor_traits.h) gets them from the azimuth at the sweep rate. A non-repetitive
// sensor's sweep keeps its single instant. Returns whether it did.
bool fill_missing_point_times(LidarScan& scan, const SensorTraits& traits, double rate_hz);

}  // namespace vilslam::lidar
