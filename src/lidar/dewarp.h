#pragma once
// Motion compensation of a sweep (paper Sec. "LiDAR scan dewarping"): every point is moved from the LiDAR
// frame at its own instant t_i to the LiDAR frame at the end of the sweep t_{k+1}.
#include <functional>

#include "common/lie.h"
#include "common/types.h"
#include "lidar/features.h"

namespace vilslam::lidar {

// The LiDAR pose in the world at any instant of the sweep, e.g. interpolated IMU-rate VIO poses.
using PoseAtTime = std::function<SE3(TimeNs)>;

// Feature points expressed in the LiDAR frame at end_t_ns; their t_offset_s becomes end_t_ns - t_ns.
FeatureScan dewarp(const FeatureScan& features, TimeNs end_t_ns, const PoseAtTime& T_W_L);

// The whole sweep expressed in the LiDAR frame at scan.end_t_ns(); t_offset_s becomes that of the end.
LidarScan dewarp(const LidarScan& scan, const PoseAtTime& T_W_L);

}  // namespace vilslam::lidar
