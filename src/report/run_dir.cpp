#include "report/run_dir.h"

#include <yaml-cpp/yaml.h>

#include <filesystem>

#include "common/error.h"
#include "common/yaml_config.h"
#include "io/csv.h"
#include "io/trajectory_io.h"

namespace vilslam::report {
namespace {

namespace fs = std::filesystem;

// The table's first row must be the header `columns` (the run writes one; comments start with '#').
void require_header(const Table& table, const std::vector<std::string>& columns) {
  if (table.rows().empty() || table.rows().front().fields != columns) {
    std::string expected;
    for (const std::string& c : columns) expected += (expected.empty() ? "" : ",") + c;
    throw InputError(table.path(), "expected the header '" + expected + "' on the first line");
  }
}

std::optional<Trajectory> read_optional_trajectory(const fs::path& file) {
  if (!fs::exists(file)) return std::nullopt;
  return read_trajectory(file.string(), TrajectoryFormat::kTum);
}

std::vector<SweepDegeneracy> read_degeneracy(const std::string& path) {
  const Table table(path, ',', 8);
  require_header(table, {"t_ns", "degenerate", "eig0", "eig1", "eig2", "eig3", "eig4", "eig5", "rms_residual_m",
                         "matched_fraction", "inlier_fraction"});
  std::vector<SweepDegeneracy> sweeps;
  std::vector<TimeNs> times;
  for (std::size_t i = 1; i < table.rows().size(); ++i) {
    const TableRow& row = table.rows()[i];
    const long flag = table.integer(row, 1);
    if (flag != 0 && flag != 1) throw InputError(path, "field 2 (degenerate) must be 0 or 1", row.line);
    sweeps.push_back({table.time_ns(row, 0), flag == 1, table.number(row, 2)});
    times.push_back(sweeps.back().t_ns);
  }
  table.require_increasing(times);
  return sweeps;
}

std::vector<TimingSamples> read_timing_samples(const std::string& path) {
  const Table table(path, ',', 2);
  require_header(table, {"series", "ms"});
  std::vector<TimingSamples> series;
  for (std::size_t i = 1; i < table.rows().size(); ++i) {
    const TableRow& row = table.rows()[i];
    const std::string& name = table.text(row, 0);
    if (series.empty() || series.back().series != name) series.push_back({name, {}});
    series.back().samples_ms.push_back(table.number(row, 1));
  }
  return series;
}

double json_number(const YAML::Node& node, const std::string& key, const std::string& file) {
  const YAML::Node value = node[key];
  if (!value || !value.IsScalar()) throw InputError(file, "missing number '" + key + "'");
  try {
    return value.as<double>();
  } catch (const YAML::Exception&) {
    throw InputError(file, "'" + key + "' is not a number: " + value.Scalar());
  }
}

// The summaries of a timings.json object: every member that is an object with median_ms.
void read_summaries(const YAML::Node& object, const std::string& file, std::vector<TimingSummaryRow>& rows) {
  for (const auto& entry : object) {
    const YAML::Node& value = entry.second;
    if (!value.IsMap() || !value["median_ms"]) continue;
    rows.push_back({entry.first.Scalar(), json_number(value, "frames", file), json_number(value, "median_ms", file),
                    json_number(value, "p95_ms", file), json_number(value, "max_ms", file)});
  }
}

// timings.json is JSON, which yaml-cpp reads as YAML (JSON is YAML's flow style).
RunTimings read_timings(const std::string& path) {
  const YAML::Node root = load_yaml_file(path);
  if (!root.IsMap()) throw InputError(path, "expected a JSON object");
  RunTimings t;
  if (!root["mode"] || !root["mode"].IsScalar()) throw InputError(path, "missing 'mode'");
  t.mode = root["mode"].Scalar();
  t.data_s = json_number(root, "data_s", path);
  t.run_wall_s = json_number(root, "run_wall_s", path);
  read_summaries(root, path, t.summaries);
  if (const YAML::Node lost = root["lidar_lost_t_ns"]) {  // absent in runs before 2026-12-06
    if (!lost.IsSequence()) throw InputError(path, "'lidar_lost_t_ns' is not an array");
    for (const YAML::Node& t_ns : lost) {
      try {
        t.lidar_lost_t_ns.push_back(t_ns.as<TimeNs>());
      } catch (const YAML::Exception&) {
        throw InputError(path, "'lidar_lost_t_ns' holds a value that is not an integer time stamp");
      }
    }
  }
  if (const YAML::Node realtime = root["realtime"]) {
    t.realtime_speed = json_number(realtime, "speed", path);
    read_summaries(realtime, path, t.summaries);
  }
  return t;
}

}  // namespace

RunDir read_run_dir(const std::string& path) {
  const fs::path dir(path);
  if (!fs::is_directory(dir)) throw InputError(path, "no such run folder");
  RunDir run;
  run.path = path;
  const fs::path timings = dir / "timings.json";
  if (!fs::exists(timings)) throw InputError(timings.string(), "missing: not a `vilslam run --out` folder");
  run.timings = read_timings(timings.string());
  if (fs::exists(dir / "timing_samples.csv"))
    run.timings.samples = read_timing_samples((dir / "timing_samples.csv").string());
  run.vio_T_W_I = read_optional_trajectory(dir / "vio_camera.tum");
  run.lidar_odometry_T_W_L = read_optional_trajectory(dir / "lidar.tum");
  run.lidar_final_T_W_L = read_optional_trajectory(dir / "lidar_final.tum");
  if (!run.vio_T_W_I && !run.lidar_odometry_T_W_L)
    throw InputError(path, "no trajectory (neither vio_camera.tum nor lidar.tum)");
  if (fs::exists(dir / "loops.csv")) run.loops = loop::read_loop_rows((dir / "loops.csv").string());
  if (fs::exists(dir / "degeneracy.csv")) run.degeneracy = read_degeneracy((dir / "degeneracy.csv").string());
  return run;
}

}  // namespace vilslam::report
