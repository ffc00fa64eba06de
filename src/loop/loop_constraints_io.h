#pragma once
// Loop constraints from a csv file (docs/formats.md, "Loop constraints"):
//   from_t_ns,to_t_ns,tx,ty,tz,qx,qy,qz,qw[,sigma_m,sigma_rad]
// The row measures T_from_to = (T_W_from)^-1 T_W_to between two poses of a trajectory (sorted by time, as
// read_trajectory returns it), found by exact time.
#include <string>
#include <vector>

#include "common/types.h"
#include "loop/pose_graph.h"

namespace vilslam::loop {

// Standard deviations of a loop row that has no sigma columns.
struct LoopSigmas {
  double sigma_m = 0.05;
  double sigma_rad = 0.01;
};

// Throws InputError naming the file and line on a missing file, a bad or non-finite field, a timestamp
// absent from poses, equal from/to times, a non-unit quaternion or a non-positive sigma.
std::vector<RelativePoseConstraint> read_loop_constraints(const std::string& path, const Trajectory& poses,
                                                          const LoopSigmas& defaults);

}  // namespace vilslam::loop
