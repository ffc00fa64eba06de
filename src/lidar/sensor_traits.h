#pragma once
// What LiDAR mapping needs to know about its sensor, read off a sweep itself (issue 60): whether its points
// lie on laser rings (a spinning multi-beam head) or fill the field of view (a non-repetitive, Livox-type
// pattern), whether they carry their own times, the field of view and the ranges. LiDAR mapping adapts its
// configuration to these (lidar/sensor_adaptation.h); `vilslam info` prints them.
#include <string>

#include "common/types.h"
#include "io/dataset_index.h"

namespace vilslam::lidar {

struct SensorTraits {
  static constexpr std::size_t kMinPoints = 100;  // fewer returns tell nothing: the traits are not read
  std::size_t points = 0;      // returns in the sweep, at a finite range of at least 1 m
  bool ring_field = false;     // the source named each point's laser
  bool point_times = false;    // the source gave each point its own time
  int rings = 0;               // laser rings seen in the elevations (the ring field's count when given); 0: none
  double min_elevation_deg = 0.0;  // 0.5 % and 99.5 % quantiles of the returns' elevations
  double max_elevation_deg = 0.0;
  double azimuth_coverage = 0.0;   // share of the 360 one-degree azimuth sectors that hold returns
  double range_p10_m = 0.0;        // quantiles of the returns' ranges
  double range_median_m = 0.0;
  double range_p90_m = 0.0;
  double range_max_m = 0.0;        // 99.5 % quantile (the farthest few are stray)

  // A spinning head sweeps its azimuth in time, so a point's azimuth gives its time when the source gave none
  // (lidar/azimuth_times.h); a non-repetitive pattern gives no such clock.
  bool spinning() const { return ring_field || rings > 0; }
  // Enough returns to tell anything (a sweep of a test rig may have a dozen): otherwise nothing adapts to them.
  bool read() const { return points >= kMinPoints; }
};

// The traits of one sweep (SensorTraits::read() false when it has too few returns).
SensorTraits read_sensor_traits(const LidarScan& sweep);

// The traits of a dataset's first sweep, as a run reads them (pipeline/lidar_feeder.h). Throws InputError naming
// the dataset when it has no sweep.
SensorTraits first_sweep_traits(const DatasetIndex& index);

// One line per trait, "name: value", as `vilslam info` prints them.
std::string sensor_traits_text(const SensorTraits& traits);

}  // namespace vilslam::lidar
