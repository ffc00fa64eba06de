#pragma once
// Mixed pixels ("veiling" points): a beam whose footprint straddles a depth edge returns a range between the
// near and the far surface, a point on neither (Tuley et al., "Analysis and removal of artifacts in 3-D LADAR
// data", ICRA 2005). Along a ring such a point lies between its two azimuth neighbours in range, far from both;
// without rings, among its nearest beams by direction it has nearer and farther ones and none at its own range.
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
  // Scans without rings (a non-repetitive sensor, no firing order along a ring): the point's nearest beams by
  // direction, at most this many and at most max_neighbour_angle_deg away, stand in for its ring neighbours.
  // A surface seen at incidence a changes the range by about r * angle * tan(a) between two beams, so without
  // rings the gap to a neighbour is at least that at max_incidence_deg (LOAM's 0.02 is it at a VLP-16's 0.2 deg).
  int direction_neighbours = 8;
  double max_neighbour_angle_deg = 3.0;
  double max_incidence_deg = 60.0;
};

// One flag per point of the scan, true for a mixed pixel: judged along each ring when the scan has rings, else by
// the nearest beams in direction.
std::vector<bool> mixed_pixels(const LidarScan& scan, const MixedPixelConfig& config = {});

}  // namespace vilslam::lidar
