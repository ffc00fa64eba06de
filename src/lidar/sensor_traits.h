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
  std::size_t points = 0;      // returns in the sweep, at a finite range above kMinTraitRange_m
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
};

// The traits of one sweep. Throws InputError when it has fewer than kMinTraitPoints usable returns.
SensorTraits read_sensor_traits(const LidarScan& sweep);

// The traits of a dataset's first sweep with enough returns, as a run reads them (pipeline/lidar_feeder.h: it
// leaves sweeps with too few returns unmapped). Throws InputError naming the dataset when no sweep has enough.
SensorTraits first_sweep_traits(const DatasetIndex& index);

// One line per trait, "name: value", as `vilslam info` prints them.
std::string sensor_traits_text(const SensorTraits& traits);

}  // namespace vilslam::lidar
