#include "report/report_json.h"

#include "common/json_writer.h"
#include "report/base64.h"
#include "report/decimate.h"

namespace vilslam::report {
namespace {

void write_f32(JsonWriter& json, const std::string& key, const std::vector<float>& values) {
  json.key(key).value(base64_float32(values));
}

// "t_s" (from t0) and "xyz" (interleaved, m) of at most max_points poses.
void write_path(JsonWriter& json, const Trajectory& T_W_B, TimeNs t0_ns, std::size_t max_points) {
  std::vector<float> t_s, xyz;
  for (std::size_t i : decimated_indices(T_W_B.size(), max_points)) {
    t_s.push_back(static_cast<float>(ns_to_s(T_W_B[i].t_ns - t0_ns)));
    for (int k = 0; k < 3; ++k) xyz.push_back(static_cast<float>(T_W_B[i].T_W_B.translation()[k]));
  }
  json.key("poses").value(static_cast<std::uint64_t>(T_W_B.size()));
  write_f32(json, "t_s", t_s);
  write_f32(json, "xyz", xyz);
}

void write_errors(JsonWriter& json, const TrajectoryErrors& e, TimeNs t0_ns, std::size_t max_points) {
  json.key("errors").begin_object();
  json.key("align").value(eval::align_mode_name(e.alignment.mode));
  json.key("matched").value(static_cast<std::uint64_t>(e.t_ns.size()));
  json.key("rmse_m").value(e.ape.trans.rmse);
  json.key("mean_m").value(e.ape.trans.mean);
  json.key("max_m").value(e.ape.trans.max);
  json.key("rot_rmse_deg").value(e.ape.rot.rmse);
  std::vector<float> t_s, travelled_m, ape_m;
  for (std::size_t i : decimated_indices(e.t_ns.size(), max_points)) {
    t_s.push_back(static_cast<float>(ns_to_s(e.t_ns[i] - t0_ns)));
    travelled_m.push_back(static_cast<float>(e.travelled_m[i]));
    ape_m.push_back(static_cast<float>(e.ape.trans_m[i]));
  }
  write_f32(json, "t_s", t_s);
  write_f32(json, "travelled_m", travelled_m);
  write_f32(json, "ape_m", ape_m);
  json.end_object();
}

void write_point(JsonWriter& json, const Vec3& p) {
  json.begin_array();
  for (int k = 0; k < 3; ++k) json.value(static_cast<double>(static_cast<float>(p[k])));
  json.end_array();
}

// Degenerate sweeps and loops as positions on the drawn trajectory `on` (a LiDAR one).
void write_events(JsonWriter& json, const ReportData& data) {
  json.key("events").begin_object();
  if (data.events_on) {
    const DrawnTrajectory& on = data.trajectories[*data.events_on];
    json.key("on").value(on.name);
    if (data.run.degeneracy) {
      std::vector<float> xyz;
      for (const SweepDegeneracy& s : *data.run.degeneracy) {
        if (!s.degenerate) continue;
        const Vec3 p = pose_at(on.T_W_B, s.t_ns).translation();
        for (int k = 0; k < 3; ++k) xyz.push_back(static_cast<float>(p[k]));
      }
      json.key("sweeps").value(static_cast<std::uint64_t>(data.run.degeneracy->size()));
      json.key("degenerate").value(static_cast<std::uint64_t>(xyz.size() / 3));
      write_f32(json, "degenerate_xyz", xyz);
    }
    if (data.run.loops) {
      json.key("loops").begin_array();
      for (const loop::LoopRow& l : *data.run.loops) {
        json.begin_object();
        json.key("from_t_s").value(ns_to_s(l.from_t_ns - data.t0_ns));
        json.key("to_t_s").value(ns_to_s(l.to_t_ns - data.t0_ns));
        json.key("from");
        write_point(json, pose_at(on.T_W_B, l.from_t_ns).translation());
        json.key("to");
        write_point(json, pose_at(on.T_W_B, l.to_t_ns).translation());
        json.end_object();
      }
      json.end_array();
    }
  }
  json.end_object();
}

void write_timings(JsonWriter& json, const ReportData& data) {
  const RunTimings& t = data.run.timings;
  json.key("timings").begin_object();
  json.key("summaries").begin_array();
  for (const TimingSummaryRow& row : t.summaries) {
    json.begin_object();
    json.key("series").value(row.series);
    json.key("frames").value(row.frames);
    json.key("median_ms").value(row.median_ms);
    json.key("p95_ms").value(row.p95_ms);
    json.key("max_ms").value(row.max_ms);
    json.end_object();
  }
  json.end_array();
  json.key("histograms").begin_array();
  for (const TimingHistogram& h : data.histograms) {
    json.begin_object();
    json.key("series").value(h.series);
    json.key("lower_ms").value(h.ms.lower);
    json.key("bin_width_ms").value(h.ms.bin_width);
    json.key("counts").begin_array();
    for (std::size_t c : h.ms.counts) json.value(static_cast<std::uint64_t>(c));
    json.end_array();
    json.end_object();
  }
  json.end_array();
  json.end_object();
}

void write_map(JsonWriter& json, const ReportData& data, const ReportOptions& options) {
  if (!data.map) return;
  const MapView& m = *data.map;
  json.key("map").begin_object();
  json.key("file").value(data.map_path);
  json.key("model").value(data.model_path);
  json.key("total_points").value(static_cast<std::uint64_t>(m.total_points));
  json.key("shown_points").value(static_cast<std::uint64_t>(m.p_map.size()));
  json.key("value_name").value(m.value_name);
  if (m.mre) {
    json.key("mre_mean_m").value(m.mre->mean_m);
    json.key("mre_median_m").value(m.mre->median_m);
    json.key("mre_p95_m").value(m.mre->p95_m);
  }
  std::vector<float> xyz;
  for (const Eigen::Vector3f& p : m.p_map) xyz.insert(xyz.end(), {p.x(), p.y(), p.z()});
  write_f32(json, "xyz", xyz);
  write_f32(json, "value", m.value);
  json.key("path").begin_object();
  write_path(json, data.map_path_T_W_L, data.t0_ns, options.max_path_points);
  json.end_object();
  json.end_object();
}

}  // namespace

std::string report_json(const ReportData& data, const ReportOptions& options) {
  JsonWriter json;
  json.begin_object();
  json.key("run").value(data.run.path);
  json.key("mode").value(data.run.timings.mode);
  json.key("data_s").value(data.run.timings.data_s);
  json.key("run_wall_s").value(data.run.timings.run_wall_s);
  if (data.run.timings.realtime_speed) json.key("realtime_speed").value(*data.run.timings.realtime_speed);
  json.key("lidar_lost_s").begin_array();
  for (TimeNs t_ns : data.run.timings.lidar_lost_t_ns) json.value(ns_to_s(t_ns - data.t0_ns));
  json.end_array();
  json.key("gt").value(data.gt_path);
  json.key("notes").begin_array();
  for (const std::string& note : data.notes) json.value(note);
  json.end_array();
  if (data.gt_T_W_B) {
    json.key("ground_truth").begin_object();
    json.key("frame").value(data.gt_frame);
    write_path(json, *data.gt_T_W_B, data.t0_ns, options.max_path_points);
    json.end_object();
  }
  json.key("trajectories").begin_array();
  for (const DrawnTrajectory& t : data.trajectories) {
    json.begin_object();
    json.key("name").value(t.name);
    json.key("file").value(t.file);
    write_path(json, t.T_W_B, data.t0_ns, options.max_path_points);
    if (t.errors) write_errors(json, *t.errors, data.t0_ns, options.max_path_points);
    json.end_object();
  }
  json.end_array();
  write_events(json, data);
  write_timings(json, data);
  write_map(json, data, options);
  json.end_object();
  return json.str();
}

}  // namespace vilslam::report
