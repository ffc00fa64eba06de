// The hallway is the paper's hard case for vision: along its route a Shi-Tomasi detector finds far
// fewer corners than along the highbay's, and far fewer that are real (found again under new noise).
#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <iostream>

#include "sim/camera_render.h"
#include "sim/scenario_figures.h"
#include "sim/sim_config.h"

namespace vilslam::sim {
namespace {

struct CornerCounts {
  double detected = 0;    // mean corners per frame (quality 0.01, min distance 10 px)
  double repeatable = 0;  // mean of those found again within 1 px in the same view with other noise
};

std::vector<cv::Point2f> corners(const cv::Mat& image) {
  std::vector<cv::Point2f> found;
  cv::goodFeaturesToTrack(image, found, 1000, 0.01, 10);
  return found;
}

CornerCounts corners_along_route(Scenario scenario, int frames) {
  const World world = World::generate(scenario, 5);
  const std::vector<Vec3>& route = world.route_W();
  CornerCounts counts;
  for (int k = 0; k < frames; ++k) {
    const SE3 T_W_C = route_camera_pose(route, k * (route.size() - 1) / frames);
    RenderOptions options;
    options.noise_seed = k;
    const std::vector<cv::Point2f> a = corners(render_image(world, default_camera(), [&](TimeNs) { return T_W_C; }, 0, options));
    options.noise_seed = 1000 + k;
    const std::vector<cv::Point2f> b = corners(render_image(world, default_camera(), [&](TimeNs) { return T_W_C; }, 0, options));
    int again = 0;
    for (const cv::Point2f& p : a) {
      again += std::any_of(b.begin(), b.end(), [&](const cv::Point2f& q) { return cv::norm(p - q) < 1.0; });
    }
    counts.detected += static_cast<double>(a.size()) / frames;
    counts.repeatable += static_cast<double>(again) / frames;
  }
  return counts;
}

TEST(CameraHardCase, HallwayHasFarFewerCornersThanHighbay) {
  const CornerCounts highbay = corners_along_route(Scenario::kHighbay, 12);
  const CornerCounts hallway = corners_along_route(Scenario::kHallway, 12);
  std::cout << "mean Shi-Tomasi corners per frame (repeatable): highbay " << highbay.detected << " ("
            << highbay.repeatable << "), hallway " << hallway.detected << " (" << hallway.repeatable << ")\n";
  EXPECT_LT(hallway.detected, 0.5 * highbay.detected);
  EXPECT_LT(hallway.repeatable, 0.2 * highbay.repeatable);
  EXPECT_GT(hallway.repeatable, 3.0) << "the hallway is hard, not blind";
}

}  // namespace
}  // namespace vilslam::sim
