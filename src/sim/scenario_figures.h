#pragma once
// The three doc figures of a scenario: the left camera image at the start of the route, one LiDAR
// sweep seen from above, and the world's surfaces from above with the route.
#include <cstdint>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "common/calibration.h"
#include "common/lie.h"
#include "sim/world.h"

namespace vilslam::sim {

// Camera pose at route waypoint i looking (level) towards the first later waypoint at least lookahead_m
// away, as a vehicle that smooths the route's corners would.
SE3 route_camera_pose(const std::vector<Vec3>& route_W, std::size_t i, double lookahead_m = 3.0);

struct ScenarioFigures {
  cv::Mat left;      // 8-bit grey
  cv::Mat scan_top;  // BGR
  cv::Mat map_top;   // BGR
};
ScenarioFigures make_scenario_figures(const World& world, std::uint64_t seed);

// Writes <scenario>_left.png, <scenario>_scan_top.png and <scenario>_map_top.png into out_dir; returns
// the paths written.
std::vector<std::string> write_scenario_figures(const World& world, std::uint64_t seed, const std::string& out_dir);

}  // namespace vilslam::sim
