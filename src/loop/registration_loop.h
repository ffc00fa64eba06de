#pragma once
// The loop a scan-to-map registration makes (docs/loop.md, "Forced resets"): a sweep registered on a map built
// from another run's key scans (a loaded map, or the run before a reset) measures its pose against them. After
// re-localizing, the first such sweep joins the global graph by this loop, taken from the nearest map key scan,
// instead of by an odometry factor holding the registration's jump.
#include <cstddef>
#include <optional>
#include <vector>

#include "common/lie.h"
#include "common/types.h"
#include "loop/key_frame.h"

namespace vilslam::loop {

struct RegistrationLoop {
  std::size_t map_pose_index = 0;  // of the nearest map key scan (its pose in map_poses)
  SE3 T_Lu_Lv;                     // from that key scan to the registered sweep
  Mat6 information;                // [rho; phi] in Lv
};

struct RegistrationLoopSigmas {
  double point_m = 0.05;       // scales the registration's J^T J, as a loop closer's ICP information
  double loop_m = 0.02;        // the floor of every loop factor's noise
  double loop_rad = 0.002;
  double degenerate_m = 0.1;   // along the directions the registration left to its prediction
  double degenerate_rad = 0.02;
};

// T_W_Lv: the registered sweep's pose in the map's frame; information_Lv: the registration's J^T J there (per m^2
// of point residual); degenerate_directions: those it left to its prediction (unit [rho; phi] in Lv), where the
// loop keeps none of its information but only the weak degenerate sigmas (a factor needs full rank; the
// prediction is in the graph anyway, as the sweep's odometry). The whole is floored by the loop sigmas. None when
// no map key scan lies within max_distance_m.
std::optional<RegistrationLoop> registration_loop(const std::vector<KeyFrame>& map_key_frames,
                                                  const Trajectory& map_poses, const SE3& T_W_Lv,
                                                  const Mat6& information_Lv,
                                                  const std::vector<Vec6>& degenerate_directions,
                                                  double max_distance_m, const RegistrationLoopSigmas& sigmas);

}  // namespace vilslam::loop
