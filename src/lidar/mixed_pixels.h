#pragma once
// Mixed pixels ("veiling" points): a beam whose footprint straddles a depth edge returns a range between the
// near and the far surface, a point on neither (Tuley et al., "Analysis and removal of artifacts in 3-D LADAR
// data", ICRA 2005). Along a ring such a point lies between its two azimuth neighbours in range, far from both.
#include <vector>

#include "common/types.h"

namespace vilslam::lidar {

struct MixedPixelConfig {
  // A point is mixed when its range lies strictly between those of its two ring neighbours and differs from
  // each by more than this fraction of its range (LOAM's 0.02 "beam nearly parallel to the surface" ratio).
  double min_gap_ratio = 0.02;
  // Neighbours count only when adjacent in firing: an azimuth step at most this many times the ring's median
  // step (a missed echo leaves a wider gap, across which the neighbour says nothing).
  double max_step_ratio = 2.5;
};

// One flag per point of the scan, true for a mixed pixel. Needs rings (scan.has_ring); a scan without
// rings (a non-repetitive sensor) has no firing order to judge by, and every flag is false.
std::vector<bool> mixed_pixels(const LidarScan& scan, const MixedPixelConfig& config = {});

}  // namespace vilslam::lidar
