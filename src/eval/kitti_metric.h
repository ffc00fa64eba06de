#pragma once
// The KITTI odometry benchmark metric (devkit evaluate_odometry.cpp): for every 10th frame as start and
// each segment length 100, 200, ..., 800 m of ground-truth path, the error of the estimated relative
// motion over the segment, E = (P_first^-1 P_last)^-1 (Q_first^-1 Q_last); translation error |t(E)| / length
// and rotation error angle(E) / length, averaged over all segments.
#include <cstddef>

#include "common/types.h"

namespace vilslam::eval {

struct KittiMetric {
  double t_err_percent = 0;    // mean translation error per length, in %
  double r_err_deg_per_m = 0;  // mean rotation error per length, in deg/m
  std::size_t segments = 0;    // 0 when the ground-truth path is shorter than 100 m
};

// gt[i] and est[i] correspond. Throws std::invalid_argument on a length mismatch.
KittiMetric compute_kitti_metric(const Trajectory& gt, const Trajectory& est);

}  // namespace vilslam::eval
