// The hallway is the paper's hard case for vision: along its route a Shi-Tomasi detector finds far
// fewer corners than along the highbay's.
#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include <iostream>

#include "sim/camera_render.h"
#include "sim/scenario_figures.h"

namespace vilslam::sim {
namespace {

// Mean corner count (quality 0.01, min distance 10 px) over frames spread along the route.
double mean_corners_along_route(Scenario scenario, int frames) {
  const World world = World::generate(scenario, 5);
  const std::vector<Vec3>& route = world.route_W();
  double total = 0;
  for (int k = 0; k < frames; ++k) {
    const SE3 T_W_C = route_camera_pose(route, k * (route.size() - 1) / frames);
    RenderOptions options;
    options.noise_seed = k;
    const cv::Mat image = render_image(world, figure_camera(), [&](TimeNs) { return T_W_C; }, 0, options);
    std::vector<cv::Point2f> corners;
    cv::goodFeaturesToTrack(image, corners, 1000, 0.01, 10);
    total += corners.size();
  }
  return total / frames;
}

TEST(CameraHardCase, HallwayHasFarFewerCornersThanHighbay) {
  const double highbay = mean_corners_along_route(Scenario::kHighbay, 8);
  const double hallway = mean_corners_along_route(Scenario::kHallway, 8);
  std::cout << "mean Shi-Tomasi corners per frame: highbay " << highbay << ", hallway " << hallway << "\n";
  EXPECT_LT(hallway, 0.5 * highbay);
  EXPECT_GT(hallway, 5.0) << "the hallway is hard, not blind";
}

}  // namespace
}  // namespace vilslam::sim
