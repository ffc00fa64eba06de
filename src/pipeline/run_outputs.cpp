#include "pipeline/run_outputs.h"

#include <algorithm>
#include <filesystem>

#include "common/json_writer.h"
#include "io/trajectory_io.h"
#include "pipeline/timing_stats.h"

namespace vilslam {
namespace {

namespace fs = std::filesystem;

void write_timing(JsonWriter& json, const std::string& name, const std::vector<double>& samples_ms) {
  const TimingSummary s = summarize_timings(samples_ms);
  json.key(name).begin_object();
  json.key("frames").value(static_cast<std::uint64_t>(s.count));
  json.key("median_ms").value(s.median_ms);
  json.key("p95_ms").value(s.p95_ms);
  json.key("max_ms").value(s.max_ms);
  json.end_object();
}

std::string timings_json(const std::string& mode, const OfflineRunResult& r) {
  JsonWriter json;
  json.begin_object();
  json.key("mode").value(mode);
  json.key("stereo_frames").value(static_cast<std::uint64_t>(r.matches_per_frame.size()));
  json.key("imu_samples").value(static_cast<std::uint64_t>(r.imu_samples));
  json.key("camera_states").value(static_cast<std::uint64_t>(r.camera_states.size()));
  json.key("imu_poses").value(static_cast<std::uint64_t>(r.imu_poses.size()));
  const auto [min_it, max_it] = std::minmax_element(r.matches_per_frame.begin(), r.matches_per_frame.end());
  json.key("matches_min").value(min_it == r.matches_per_frame.end() ? 0 : *min_it);
  json.key("matches_max").value(max_it == r.matches_per_frame.end() ? 0 : *max_it);
  write_timing(json, "frontend", r.frontend_ms);
  write_timing(json, "smoother", r.smoother_ms);
  json.end_object();
  return json.str();
}

}  // namespace

void write_run_outputs(const std::string& out_dir, const std::string& mode, const OfflineRunResult& result) {
  fs::path out = fs::path(out_dir).lexically_normal();
  if (!out.has_filename()) out = out.parent_path();  // "DIR/"
  const fs::path partial = out.string() + ".partial";
  fs::remove_all(partial);
  fs::create_directories(partial);
  write_trajectory((partial / "vio_camera.tum").string(), result.camera_states, TrajectoryFormat::kTum);
  write_trajectory((partial / "vio_imu.tum").string(), result.imu_poses, TrajectoryFormat::kTum);
  write_file_atomic((partial / "timings.json").string(), timings_json(mode, result));
  fs::remove_all(out);
  fs::rename(partial, out);
}

}  // namespace vilslam
