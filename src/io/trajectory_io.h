#pragma once
// Trajectories in and out: TUM (t x y z qx qy qz qw, seconds), KITTI (3x4 row-major, no times;
// times from a separate times file or the row index), EuRoC csv (ns, p, q_wxyz[, v, b_w, b_a]).
#include <string>

#include "common/types.h"

namespace vilslam {

enum class TrajectoryFormat { kTum, kKitti, kEuroc };

// "tum" | "kitti" | "euroc"; throws std::invalid_argument otherwise.
TrajectoryFormat parse_trajectory_format(const std::string& name);
// Guess from the extension and the first data row.
TrajectoryFormat detect_trajectory_format(const std::string& path);

// Throws InputError naming file and line on missing files, bad rows, NaNs, decreasing timestamps. A TUM or
// EuRoC row repeating the previous time is dropped with a warning naming file and line (benchmark files do it).
// For KITTI files without times, pose i gets t_ns = i seconds unless times_path is given.
Trajectory read_trajectory(const std::string& path, TrajectoryFormat format, const std::string& times_path = {});
void write_trajectory(const std::string& path, const Trajectory& traj, TrajectoryFormat format);

}  // namespace vilslam
