#include "sim/scenario_figures.h"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "sim/camera_rays.h"
#include "sim/camera_render.h"
#include "sim/figures.h"
#include "sim/lidar_sim.h"
#include "sim/sim_config.h"

namespace vilslam::sim {
namespace {

constexpr int kFigureSidePx = 800;

// Level direction from waypoint i to the first later waypoint at least min_m away (wrapping).
Vec3 route_heading(const std::vector<Vec3>& route_W, std::size_t i, double min_m) {
  for (std::size_t k = 1; k < route_W.size(); ++k) {
    Vec3 d = route_W[(i + k) % route_W.size()] - route_W[i];
    d.z() = 0;
    if (d.norm() >= min_m) return d.normalized();
  }
  return Vec3::UnitX();
}

cv::Mat scan_top_view(const World& world, const Vec3& origin_W, const Vec3& heading_W, std::uint64_t seed) {
  const Vec3 left_W = Vec3::UnitZ().cross(heading_W);
  Mat3 R_W_L;
  R_W_L << heading_W, left_W, Vec3::UnitZ();
  const SE3 T_W_L(R_W_L, origin_W);
  const LidarScan scan = simulate_sweep(world, LidarSimConfig{}, 0, [&](TimeNs) { return T_W_L; }, seed);
  std::vector<Eigen::Vector3f> points;
  std::vector<double> ranges;
  for (const LidarPoint& p : scan.points) {
    points.emplace_back(p.x, p.y, p.z);
    ranges.push_back(std::hypot(p.x, p.y));
  }
  double radius = 10;
  if (!ranges.empty()) {
    // Frame the 98 % nearest points: the few far returns would shrink the rest to a dot.
    auto q = ranges.begin() + static_cast<std::ptrdiff_t>(0.98 * (ranges.size() - 1));
    std::nth_element(ranges.begin(), q, ranges.end());
    radius = std::max(radius, 1.05 * *q);
  }
  TopView view(Eigen::AlignedBox2d(Eigen::Vector2d(-radius, -radius), Eigen::Vector2d(radius, radius)), kFigureSidePx);
  view.draw_points(points, -2.0, 3.0, 1e9, 2);
  view.draw_path({Vec3::Zero(), Vec3(0.1 * radius, 0, 0)}, cv::Scalar(0, 0, 0), 2);
  view.draw_scale_bar();
  return view.image().clone();
}

cv::Mat map_top_view(const World& world) {
  const Eigen::AlignedBox3d b = world.bounds();
  // At least a quarter as high as wide, so that long thin worlds (tunnels) stay visible.
  const Eigen::Vector2d half_size =
      (0.5 * b.sizes().head<2>()).cwiseMax(0.125 * b.sizes().head<2>().maxCoeff()) + Eigen::Vector2d::Constant(1.0);
  const Eigen::Vector2d centre = b.center().head<2>();
  const Eigen::AlignedBox2d extent(centre - half_size, centre + half_size);
  const double spacing_m = std::max(0.05, 0.7 * extent.sizes().maxCoeff() / kFigureSidePx);
  const PointCloud cloud = world.sample_surfaces(spacing_m);
  double route_z = 0;
  for (const Vec3& p : world.route_W()) route_z += p.z() / static_cast<double>(world.route_W().size());
  // Cut 1 m above the route so ceilings and roofs do not hide the floor plan; floors and ground drop out.
  const double z_clip = route_z + 1.0;
  TopView view(extent, kFigureSidePx);
  view.draw_points(cloud.points, b.min().z(), z_clip, z_clip, 2, 0.2);
  view.draw_path(world.route_W(), cv::Scalar(0, 0, 0), 2);
  view.draw_scale_bar();
  return view.image().clone();
}

}  // namespace

SE3 route_camera_pose(const std::vector<Vec3>& route_W, std::size_t i, double lookahead_m) {
  return camera_pose_looking(route_W[i], route_heading(route_W, i, lookahead_m));
}

ScenarioFigures make_scenario_figures(const World& world, std::uint64_t seed) {
  const std::vector<Vec3>& route = world.route_W();
  const SE3 T_W_C = route_camera_pose(route, 0);
  RenderOptions options;
  options.noise_seed = seed;
  ScenarioFigures f;
  f.left = render_image(world, default_camera(), [&](TimeNs) { return T_W_C; }, 0, options);
  f.scan_top = scan_top_view(world, route.front(), route_heading(route, 0, 3.0), seed);
  f.map_top = map_top_view(world);
  return f;
}

std::vector<std::string> write_scenario_figures(const World& world, std::uint64_t seed, const std::string& out_dir) {
  const ScenarioFigures f = make_scenario_figures(world, seed);
  const std::string stem = (std::filesystem::path(out_dir) / scenario_name(world.scenario())).string();
  const std::vector<std::pair<std::string, const cv::Mat*>> files{
      {stem + "_left.png", &f.left}, {stem + "_scan_top.png", &f.scan_top}, {stem + "_map_top.png", &f.map_top}};
  std::vector<std::string> written;
  for (const auto& [path, image] : files) {
    write_png(path, *image);
    written.push_back(path);
  }
  return written;
}

}  // namespace vilslam::sim
