// `vilslam eval-map --map FILE --model FILE [--first-pose POSES --gt GT] ...`: map registration error (MRE) of
// a map cloud against a reference model, after ICP alignment from the identity or from the first-pose rule
// (docs/evaluation.md).
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <memory>
#include <stdexcept>
#include <string>

#include "common/error.h"
#include "common/lie.h"
#include "common/json_writer.h"
#include "eval/eval_json.h"
#include "eval/map_error.h"
#include "io/cloud_io.h"
#include "io/dataset_groundtruth.h"
#include "io/trajectory_io.h"
#include "vilslam/command.h"

namespace {

using namespace vilslam;

struct Options {
  std::string map_path, model_path, json_path, colored_path;
  std::string first_pose_path, gt_path, align_on_path;
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

// The first-pose rule (eval/map_error.h) from the files: POSES the LiDAR poses the map was built with, GT
// a dataset folder (its ground truth in the LiDAR frame) or a TUM file of LiDAR poses in the model's frame.
eval::InitialAlignment first_pose_from_files(const std::string& poses_path, const std::string& gt_path) {
  const Trajectory est = read_trajectory(poses_path, TrajectoryFormat::kTum);
  if (est.empty()) throw InputError(poses_path, "no poses");
  const Trajectory gt = read_groundtruth(gt_path, GroundTruthFrame::kLidar);
  try {
    return eval::first_pose_alignment(est, gt);
  } catch (const std::invalid_argument& err) {
    throw InputError(poses_path, std::string("cannot align by the first pose with ") + gt_path + ": " + err.what());
  }
}

// "t [x, y, z] m, rotation A deg".
std::string pose_text(const SE3& T) {
  char buf[160];
  std::snprintf(buf, sizeof buf, "t [%.4f, %.4f, %.4f] m, rotation %.3f deg", T.translation().x(), T.translation().y(),
                T.translation().z(), so3::log(T.quat()).norm() * 180.0 / M_PI);
  return buf;
}

vilslam::cli::Command reg("eval-map", "Map registration error (MRE) of a map cloud against a reference model",
                          [](CLI::App& app) {
  auto o = std::make_shared<Options>();
  app.add_option("--map", o->map_path, "Map cloud (.ply, .pcd, .bin)")->required();
  app.add_option("--model", o->model_path, "Reference model cloud (.ply, .pcd, .bin)")->required();
  app.add_option("--icp", o->icp, "ICP error metric")
      ->check(CLI::IsMember({"point2point", "point2plane"}))
      ->capture_default_str();
  auto* first_pose = app.add_option("--first-pose", o->first_pose_path,
                                    "LiDAR poses T_W_L (TUM) the map was built with: ICP starts from the first-pose "
                                    "alignment T_gt(t0) T_est(t0)^-1 (needs --gt)");
  auto* gt = app.add_option("--gt", o->gt_path, "Ground truth of --first-pose: a dataset folder or a TUM file of T_W_L");
  first_pose->needs(gt);
  gt->needs(first_pose);
  app.add_option("--align-on", o->align_on_path,
                 "Find the alignment on this cloud (the whole map, same frame as --map) and measure --map under it");
  app.add_flag("--no-align", o->no_align, "No ICP: measure the map as given (or moved by the first-pose alignment)");
  app.add_option("--max-corr", o->max_correspondence_m, "ICP correspondence distance limit, m")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  app.add_option("--max-iter", o->max_iterations, "ICP iteration limit")->check(CLI::PositiveNumber)->capture_default_str();
  app.add_option("--icp-points", o->icp_points, "At most this many map points (every k-th) take part in ICP; 0 = all")
      ->capture_default_str();
  app.add_option("--json", o->json_path, "Also write the results as JSON to this file");
  app.add_option("--colored", o->colored_path, "Write the aligned map with per-point error as intensity (.ply/.pcd)");
  return [o]() {
    eval::MapErrorConfig config;
    if (!o->first_pose_path.empty()) config.initial = first_pose_from_files(o->first_pose_path, o->gt_path);
    const PointCloud map = read_cloud(o->map_path);
    const PointCloud model = read_cloud(o->model_path);
    const PointCloud align_map = o->align_on_path.empty() ? PointCloud{} : read_cloud(o->align_on_path);
    if (map.points.empty()) throw InputError(o->map_path, "cloud has no points");
    if (model.points.empty()) throw InputError(o->model_path, "cloud has no points");
    if (!o->align_on_path.empty() && align_map.points.empty()) throw InputError(o->align_on_path, "cloud has no points");
    config.align = !o->no_align;
    config.icp.mode = o->icp == "point2point" ? eval::IcpMode::kPointToPoint : eval::IcpMode::kPointToPlane;
    config.icp.max_correspondence_m = o->max_correspondence_m;
    config.icp.max_iterations = o->max_iterations;
    config.max_icp_points = o->icp_points;
    eval::MapError e;
    try {
      e = o->align_on_path.empty() ? eval::compute_map_error(map, model, config)
                                   : eval::compute_map_error(map, align_map, model, config);
    } catch (const std::invalid_argument& err) {
      throw InputError(o->map_path, std::string("cannot register against ") + o->model_path + ": " + err.what());
    }
    if (config.initial.first_pose_t_ns)
      std::printf("initial alignment: first pose at %.9f s, T_model_map %s\n", ns_to_s(*config.initial.first_pose_t_ns),
                  pose_text(config.initial.T_model_map).c_str());
    else
      std::printf("initial alignment: identity\n");
    if (!o->align_on_path.empty()) std::printf("alignment found on: %s\n", o->align_on_path.c_str());
    std::printf("points: %zu\nICP: %s, %d iterations, %s, %zu inliers, rmse %.5f m\n", e.per_point_m.size(),
                config.align ? o->icp.c_str() : "off", e.icp.iterations, e.icp.converged ? "converged" : "not converged",
                e.icp.inliers, e.icp.rmse_m);
    if (config.align)
      std::printf("ICP moved the map from the initial alignment by %s (%d unconstrained directions kept)\n",
                  pose_text(e.icp.T_model_map * config.initial.T_model_map.inverse()).c_str(),
                  e.icp.degenerate_directions);
    std::printf("MRE: mean %.5f m  median %.5f m  p95 %.5f m\n", e.mean_m, e.median_m, e.p95_m);
    if (config.align && !e.icp.converged)
      std::fprintf(stderr, "warning: ICP did not converge; the map may not start close to the model's frame "
                           "(ICP only pairs points within --max-corr %.2f m)%s\n", o->max_correspondence_m,
                   config.initial.first_pose_t_ns ? "" : "; a map in the estimator's frame needs --first-pose and --gt");
    if (!o->json_path.empty()) write_file_atomic(o->json_path, eval::map_error_json(e, config));
    if (!o->colored_path.empty()) write_cloud(o->colored_path, colored(map, e));
    return 0;
  };
});

}  // namespace
