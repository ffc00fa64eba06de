#pragma once
// Per-point times of a spinning sweep that came without them (a KITTI .bin, a PCD or PointCloud2 with no time
// field): each point is given the instant the sensor head swept its azimuth, as LOAM and FAST-LIO do, so that
// dewarping can still move it. Applied by the pipeline and the dense map when they dewarp (docs/lidar.md,
// "Per-point time").
#include "common/calibration.h"
#include "common/types.h"

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

// The rule of the pipeline and the dense map: a sweep without per-point times from a spinning LiDAR (the
// calibration has rings) gets them from the azimuth at the calibration's rate. Returns whether it did.
bool fill_missing_point_times(LidarScan& scan, const LidarIntrinsics& lidar);

}  // namespace vilslam::lidar
