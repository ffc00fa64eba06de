// `vilslam eval-map --map FILE --model FILE ...`: map registration error (MRE) of a map cloud against a
// reference model, after ICP alignment (docs/evaluation.md).
#include <cstddef>
#include <cstdio>
#include <memory>
#include <stdexcept>
#include <string>

#include "common/error.h"
#include "common/json_writer.h"
#include "eval/eval_json.h"
#include "eval/map_error.h"
#include "io/cloud_io.h"
#include "vilslam/command.h"

namespace {

using namespace vilslam;

struct Options {
  std::string map_path, model_path, json_path, colored_path;
  std::string icp = "point2plane";
  bool no_align = false;
  double max_correspondence_m = 1.0;
  int max_iterations = 50;
  std::size_t icp_points = eval::MapErrorConfig{}.max_icp_points;
};

// The map in the model frame, with each point's error as its intensity.
PointCloud colored(const PointCloud& map, const eval::MapError& e) {
  PointCloud out;
  out.points.reserve(map.size());
  for (const auto& p : map.points) out.points.push_back((e.icp.T_model_map * p.cast<double>()).cast<float>());
  out.intensity = e.per_point_m;
  return out;
}

vilslam::cli::Command reg("eval-map", "Map registration error (MRE) of a map cloud against a reference model",
                          [](CLI::App& app) {
  auto o = std::make_shared<Options>();
  app.add_option("--map", o->map_path, "Map cloud (.ply, .pcd, .bin)")->required();
  app.add_option("--model", o->model_path, "Reference model cloud (.ply, .pcd, .bin)")->required();
  app.add_option("--icp", o->icp, "ICP error metric")
      ->check(CLI::IsMember({"point2point", "point2plane"}))
      ->capture_default_str();
  app.add_flag("--no-align", o->no_align, "Measure the map as given, without ICP");
  app.add_option("--max-corr", o->max_correspondence_m, "ICP correspondence distance limit, m")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  app.add_option("--max-iter", o->max_iterations, "ICP iteration limit")->check(CLI::PositiveNumber)->capture_default_str();
  app.add_option("--icp-points", o->icp_points, "At most this many map points (every k-th) take part in ICP; 0 = all")
      ->capture_default_str();
  app.add_option("--json", o->json_path, "Also write the results as JSON to this file");
  app.add_option("--colored", o->colored_path, "Write the aligned map with per-point error as intensity (.ply/.pcd)");
  return [o]() {
    const PointCloud map = read_cloud(o->map_path);
    const PointCloud model = read_cloud(o->model_path);
    if (map.points.empty()) throw InputError(o->map_path, "cloud has no points");
    if (model.points.empty()) throw InputError(o->model_path, "cloud has no points");
    eval::MapErrorConfig config;
    config.align = !o->no_align;
    config.icp.mode = o->icp == "point2point" ? eval::IcpMode::kPointToPoint : eval::IcpMode::kPointToPlane;
    config.icp.max_correspondence_m = o->max_correspondence_m;
    config.icp.max_iterations = o->max_iterations;
    config.max_icp_points = o->icp_points;
    eval::MapError e;
    try {
      e = eval::compute_map_error(map, model, config);
    } catch (const std::invalid_argument& err) {
      throw InputError(o->map_path, std::string("cannot register against ") + o->model_path + ": " + err.what());
    }
    std::printf("points: %zu\nICP: %s, %d iterations, %s, %zu inliers, rmse %.5f m\n", e.per_point_m.size(),
                config.align ? o->icp.c_str() : "off", e.icp.iterations, e.icp.converged ? "converged" : "not converged",
                e.icp.inliers, e.icp.rmse_m);
    std::printf("MRE: mean %.5f m  median %.5f m  p95 %.5f m\n", e.mean_m, e.median_m, e.p95_m);
    if (config.align && !e.icp.converged)
      std::fprintf(stderr, "warning: ICP did not converge; the map may not start close to the model's frame "
                           "(ICP only pairs points within --max-corr %.2f m)\n", o->max_correspondence_m);
    if (!o->json_path.empty()) write_file_atomic(o->json_path, eval::map_error_json(e, config));
    if (!o->colored_path.empty()) write_cloud(o->colored_path, colored(map, e));
    return 0;
  };
});

}  // namespace
