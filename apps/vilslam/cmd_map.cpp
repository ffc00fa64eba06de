// `vilslam map DATASET --poses lidar.tum --out map.ply [--start-s S] [--end-s E]`: the dense map of the sweeps
// stitched with the given LiDAR poses, optionally of the sweeps ending in a time window only (docs/map.md).
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <optional>
#include <memory>
#include <stdexcept>
#include <string>

#include "common/progress.h"
#include "common/error.h"
#include "io/cloud_io.h"
#include "io/trajectory_io.h"
#include "map/map_builder.h"
#include "vilslam/command.h"

namespace {

using namespace vilslam;

struct Options {
  std::string dataset, poses_path, out_path, motion_path;
  map::MapBuilderConfig config;
  unsigned min_hits = 1;
  bool no_dewarp = false;
  bool keep_mixed_pixels = false;
  bool also_pcd = false;
  std::optional<double> start_s, end_s;  // window, seconds after the first pose
};

// The window [start, end) in the IMU clock, from seconds after the first pose (open ends stay open).
void set_window(const Options& o, TimeNs first_pose_t_ns, map::MapBuilderConfig* config) {
  for (const auto& [name, value] : {std::pair{"--start-s", o.start_s}, std::pair{"--end-s", o.end_s}})
    if (value && !std::isfinite(*value)) throw std::invalid_argument(std::string(name) + " must be finite");
  if (o.start_s) config->window_start_ns = first_pose_t_ns + s_to_ns(*o.start_s);
  if (o.end_s) config->window_end_ns = first_pose_t_ns + s_to_ns(*o.end_s);
}

// The run that made the poses (its lidar_sensor.txt beside them) took sweeps without point times as instants.
bool run_took_instants(const std::string& poses_path) {
  std::ifstream in(std::filesystem::path(poses_path).parent_path() / "lidar_sensor.txt");
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("lidar_azimuth_times: ", 0) == 0) return line != "lidar_azimuth_times: yes";
  }
  return false;
}

void check_cloud_extension(const std::string& path) {
  const std::string ext = std::filesystem::path(path).extension().string();
  if (ext != ".ply" && ext != ".pcd") throw std::invalid_argument("--out must end in .ply or .pcd: " + path);
}

vilslam::cli::Command reg("map", "Dense map: the dataset's sweeps dewarped and stitched with LiDAR poses",
                          [](CLI::App& app) {
  auto o = std::make_shared<Options>();
  app.add_option("dataset", o->dataset, "Dataset folder")->required();
  app.add_option("--poses", o->poses_path, "LiDAR poses T_W_L, TUM (e.g. lidar.tum of `vilslam run`)")->required();
  app.add_option("--out", o->out_path, "Map cloud to write (.ply or .pcd)")->required();
  app.add_option("--voxel", o->config.voxel_size_m, "Voxel size, m")->capture_default_str();
  app.add_option("--min-hits", o->min_hits, "Keep voxels with at least this many points")->capture_default_str();
  app.add_option("--min-range", o->config.min_range_m, "Drop returns closer than this, m")->capture_default_str();
  app.add_option("--max-range", o->config.max_range_m, "Drop returns farther than this, m")->capture_default_str();
  app.add_flag("--no-dewarp", o->no_dewarp, "Do not dewarp sweeps (every point takes the sweep-end pose)");
  app.add_flag("--keep-mixed-pixels", o->keep_mixed_pixels,
               "Keep mixed pixels (returns between a near and a far surface at a depth edge; docs/map.md)");
  app.add_option("--mixed-gap-ratio", o->config.mixed_pixels.min_gap_ratio,
                 "A mixed pixel's range differs from both ring neighbours' by more than this fraction of it")
      ->capture_default_str();
  app.add_option("--motion", o->motion_path,
                 "Continuous LiDAR trajectory (TUM, e.g. lidar.tum) for the motion within each sweep; --poses then "
                 "only places each sweep's end (use with lidar_global.tum, whose loop corrections jump)");
  app.add_flag("--pcd", o->also_pcd, "Also write the map as binary PCD next to --out");
  app.add_option("--start-s", o->start_s,
                 "Only sweeps ending at or after this many seconds after the first pose of --poses");
  app.add_option("--end-s", o->end_s, "Only sweeps ending before this many seconds after the first pose of --poses");
  return [o]() {
    check_cloud_extension(o->out_path);
    const Trajectory T_W_L = read_trajectory(o->poses_path, TrajectoryFormat::kTum);
    if (T_W_L.empty()) throw InputError(o->poses_path, "no poses");
    o->config.dewarp = !o->no_dewarp;
    o->config.azimuth_times = !run_took_instants(o->poses_path);
    o->config.drop_mixed_pixels = !o->keep_mixed_pixels;
    if (!o->motion_path.empty()) o->config.motion = read_trajectory(o->motion_path, TrajectoryFormat::kTum);
    set_window(*o, T_W_L.front().t_ns, &o->config);
    const map::MapBuildResult built = [&] {
      Progress progress("map", 1.0);
      return map::build_dense_map(o->dataset, T_W_L, o->config, [&progress](double f) { progress.update(f); });
    }();
    PointCloud cloud;
    cloud.points = built.map.points(o->min_hits);
    if (cloud.points.empty()) throw InputError(o->dataset, "no voxel has " + std::to_string(o->min_hits) + " hits");
    write_cloud(o->out_path, cloud);
    if (o->also_pcd) write_cloud(std::filesystem::path(o->out_path).replace_extension(".pcd").string(), cloud);
    const map::MapBuildStats& s = built.stats;
    std::printf("sweeps: %zu used, %zu skipped (not covered by the poses)", s.sweeps_used, s.sweeps_skipped);
    if (o->start_s || o->end_s)
      std::printf(", %zu outside the window (sweep ends from %.3f to before %.3f s after the first pose)",
                  s.sweeps_outside_window, o->start_s.value_or(-INFINITY), o->end_s.value_or(INFINITY));
    std::printf("\n");
    std::printf("points: %zu inserted, %zu out of range, %zu mixed pixels dropped\n", s.points_inserted,
                s.points_out_of_range, s.points_mixed);
    std::printf("voxels: %zu of %.4f m, %zu written (min hits %u), map memory %.1f MB\n", built.map.num_voxels(),
                built.map.voxel_size_m(), cloud.size(), o->min_hits, built.map.memory_bytes() / 1e6);
    return 0;
  };
});

}  // namespace
