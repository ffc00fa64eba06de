#include "eval/eval_json.h"

#include <cstdint>

#include "common/json_writer.h"

namespace vilslam::eval {
namespace {

void write_stats(JsonWriter& json, const std::string& key, const ErrorStats& s) {
  json.key(key).begin_object();
  json.key("rmse").value(s.rmse);
  json.key("mean").value(s.mean);
  json.key("median").value(s.median);
  json.key("std").value(s.std);
  json.key("min").value(s.min);
  json.key("max").value(s.max);
  json.end_object();
}

void write_matrix(JsonWriter& json, const std::string& key, const Mat4& M) {
  json.key(key).begin_array();
  for (int r = 0; r < 4; ++r) {
    json.begin_array();
    for (int c = 0; c < 4; ++c) json.value(M(r, c));
    json.end_array();
  }
  json.end_array();
}

}  // namespace

std::string trajectory_report_json(const TrajectoryEvalReport& r, const TrajectoryEvalConfig& config) {
  JsonWriter json;
  json.begin_object();
  write_stats(json, "ape", r.ape.trans);
  write_stats(json, "ape_rot_deg", r.ape.rot);
  write_stats(json, "rpe", r.rpe.trans);
  write_stats(json, "rpe_rot_deg", r.rpe.rot);
  json.key("rpe_delta").begin_object();
  json.key("value").value(config.rpe.delta);
  json.key("unit").value(config.rpe.unit == DeltaUnit::kMeters ? "m" : "frames");
  json.key("pairs").value(static_cast<std::uint64_t>(r.rpe.trans.count));
  json.end_object();
  json.key("kitti").begin_object();
  if (r.kitti.segments > 0) {
    json.key("t_err_percent").value(r.kitti.t_err_percent);
    json.key("r_err_deg_per_m").value(r.kitti.r_err_deg_per_m);
  } else {
    json.key("t_err_percent").null();
    json.key("r_err_deg_per_m").null();
  }
  json.key("segments").value(static_cast<std::uint64_t>(r.kitti.segments));
  json.end_object();
  if (r.tilt_deg.count > 0) write_stats(json, "tilt_deg", r.tilt_deg);
  json.key("fde_percent").value(r.fde.percent);
  json.key("fde_start_aligned_percent").value(r.fde_start_aligned.percent);
  json.key("path_length_m").value(r.path_length_m);
  json.key("matched_poses").value(static_cast<std::uint64_t>(r.matched_poses));
  json.key("reference_coverage").value(r.reference_coverage);
  json.key("alignment").begin_object();
  json.key("mode").value(align_mode_name(r.alignment.mode));
  json.key("first_n").value(static_cast<std::uint64_t>(config.align_first_n));
  json.key("scale").value(r.alignment.scale);
  write_matrix(json, "T", r.alignment.T_gt_est.matrix());
  json.end_object();
  json.end_object();
  return json.str();
}

std::string map_error_json(const MapError& e, const MapErrorConfig& config) {
  JsonWriter json;
  json.begin_object();
  json.key("points").value(static_cast<std::uint64_t>(e.per_point_m.size()));
  json.key("mean_m").value(e.mean_m);
  json.key("median_m").value(e.median_m);
  json.key("p95_m").value(e.p95_m);
  json.key("aligned").value(config.align);
  json.key("initial_alignment").begin_object();
  json.key("rule").value(config.initial.first_pose_t_ns ? "first_pose" : "identity");
  if (config.initial.first_pose_t_ns) {
    json.key("first_pose_t_ns").value(static_cast<std::int64_t>(*config.initial.first_pose_t_ns));
  } else {
    json.key("first_pose_t_ns").null();
  }
  write_matrix(json, "T_model_map", config.initial.T_model_map.matrix());
  json.end_object();
  json.key("icp").begin_object();
  json.key("mode").value(config.icp.mode == IcpMode::kPointToPlane ? "point_to_plane" : "point_to_point");
  json.key("iterations").value(e.icp.iterations);
  json.key("converged").value(e.icp.converged);
  json.key("inliers").value(static_cast<std::uint64_t>(e.icp.inliers));
  json.key("rmse_m").value(e.icp.rmse_m);
  json.key("max_correspondence_m").value(config.icp.max_correspondence_m);
  write_matrix(json, "T_model_map", e.icp.T_model_map.matrix());
  json.end_object();
  json.end_object();
  return json.str();
}

}  // namespace vilslam::eval
