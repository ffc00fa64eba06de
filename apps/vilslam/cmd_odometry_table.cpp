// `vilslam odometry-table --work DIR [--presets a,b] [--seed S] [--preview] [--ideal-sensors] [--config RUN_YAML] [--map-voxel M |
// --no-maps] [--reuse-runs] [--out FILE] [--note TEXT]`: simulates (or reuses) each preset, runs `vil` and
// `lidar-only` (or, with --reuse-runs, reads a run folder made with the same config), and
// writes the paper's Table I with odometry, loop-closed drift, loops and the MRE of the dense maps
// (docs/odometry.md, src/eval/odometry_table.h).
#include <spdlog/spdlog.h>
#include <sys/utsname.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "common/progress.h"
#include "common/error.h"
#include "common/json_writer.h"
#include "eval/map_error.h"
#include "eval/odometry_markdown.h"
#include "eval/odometry_table.h"
#include "io/cloud_io.h"
#include "io/dataset.h"
#include "io/dataset_groundtruth.h"
#include "io/trajectory_io.h"
#include "loop/loop_constraints_io.h"
#include "map/map_builder.h"
#include "pipeline/offline_runner.h"
#include "pipeline/run_config.h"
#include "pipeline/run_outputs.h"
#include "sim/simulator.h"
#include "vilslam/command.h"

namespace {

using namespace vilslam;
namespace fs = std::filesystem;

struct Options {
  std::string work;
  std::vector<std::string> presets = {"highbay", "hallway", "tunnel"};
  std::uint64_t seed = 1;
  bool preview = false;
  bool ideal_sensors = false;  // simulate without sensor realism (docs/simulator.md)
  std::string config_path;  // run YAML of both runs; empty: built-in defaults
  double map_voxel_m = 0.05;  // voxels of the dense maps the MRE is measured on
  bool no_maps = false;
  bool reuse_runs = false;  // read WORK/<preset>_<mode> when its config.yaml is this table's run config
  std::string out = "docs/odometry.md";
  std::string note;
};

// The simulator renames its folder into place, then moves kitti/ and groundtruth.tum in last.
bool complete_simulation(const fs::path& dir) {
  for (const char* part : {"rig.yaml", "mav0", "model.ply", "kitti/poses.txt", "groundtruth.tum"})
    if (!fs::exists(dir / part)) return false;
  return true;
}

// Reuses DIR/<preset> when it holds a complete simulation, else simulates it there; returns the table's note.
std::string prepare_dataset(const fs::path& data, const std::string& preset, const Options& o) {
  if (fs::exists(data)) {
    if (!complete_simulation(data))
      throw InputError(data.string(), "holds no complete simulation (rig.yaml, mav0, model.ply, kitti, groundtruth.tum); "
                                      "remove it or let its simulation finish");
    const std::string target = fs::is_symlink(data) ? " → `" + fs::canonical(data).string() + "`" : "";
    return "reused `" + data.string() + "`" + target;
  }
  sim::SimulateRequest request;
  request.scenario = sim::parse_scenario(preset);
  request.out_dir = data.string();
  request.seed = o.seed;
  request.preview = o.preview;
  spdlog::info("odometry-table: simulating {} (seed {}) into {}", preset, o.seed, data.string());
  sim::SimConfig config;
  config.sensor_realism = !o.ideal_sensors;
  sim::simulate(config, request);
  return "simulated, seed " + std::to_string(o.seed) + (o.preview ? ", preview" : "") +
         (o.ideal_sensors ? ", ideal sensors" : "");
}

// What the table needs of one run, from the run itself or from its output folder.
struct ModeRun {
  std::string failure;         // the run threw (bad input is not a failure: it propagates)
  Trajectory camera_states;    // vil: the VIO's camera-rate states T_W_I
  Trajectory lidar;            // the LiDAR odometry T_W_L (vil with loop closure: its composed motion, lidar.tum)
  std::size_t degenerate = 0;  // sweeps flagged degenerate
  std::optional<eval::LoopClosureInputs> loops;  // vil: candidates examined and the accepted loops
  Trajectory lidar_final;      // vil: lidar_final.tum
};

ModeRun outputs_of(const OfflineRunResult& result) {
  ModeRun run;
  run.camera_states = result.camera_states;
  for (const lidar::LidarMappingResult& m : result.lidar) {
    run.lidar.push_back({m.t_ns, m.T_W_L});
    run.degenerate += m.degenerate ? 1 : 0;
  }
  if (!result.loop) return run;
  const LoopClosureOutput& loop = *result.loop;
  run.lidar = loop.lidar_odometry;
  run.lidar_final = loop.lidar_final;
  eval::LoopClosureInputs loops;
  loops.candidates_examined = loop.candidates.size();
  for (const loop::LoopCandidateRecord& c : loop.candidates)
    if (c.accepted()) loops.accepted.push_back({c.candidate_t_ns, c.query_t_ns, c.T_Lu_Lv, c.T_Lu_Lv_epnp});
  run.loops = std::move(loops);
  return run;
}

std::string file_text(const fs::path& path) {
  std::ifstream in(path);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

std::size_t data_rows(const fs::path& csv) {
  std::ifstream in(csv);
  std::size_t rows = 0;
  for (std::string line; std::getline(in, line);) rows += !line.empty() && line[0] != '#';
  return rows;
}

// A run folder of `vilslam run` (docs/pipeline.md) read back; nullopt when it is incomplete or was made with
// another config (then the table runs again).
std::optional<ModeRun> read_run_folder(const fs::path& out, const std::string& config_yaml, RunMode mode) {
  std::vector<std::string> files = {"config.yaml", "lidar.tum", "degeneracy.csv"};
  if (mode == RunMode::kVil) files.insert(files.end(), {"vio_camera.tum", "lidar_final.tum", "loops.csv",
                                                          "loop_candidates.csv"});
  for (const std::string& f : files)
    if (!fs::exists(out / f)) return std::nullopt;
  if (file_text(out / "config.yaml") != config_yaml) {
    spdlog::info("odometry-table: {} was made with another config, running again", out.string());
    return std::nullopt;
  }
  ModeRun run;
  run.lidar = read_trajectory((out / "lidar.tum").string(), TrajectoryFormat::kTum);
  std::ifstream degeneracy(out / "degeneracy.csv");
  std::string line;
  std::getline(degeneracy, line);  // header
  while (std::getline(degeneracy, line)) {
    const std::size_t comma = line.find(',');
    run.degenerate += comma != std::string::npos && line.compare(comma + 1, 2, "1,") == 0;
  }
  if (mode != RunMode::kVil) return run;
  run.camera_states = read_trajectory((out / "vio_camera.tum").string(), TrajectoryFormat::kTum);
  run.lidar_final = read_trajectory((out / "lidar_final.tum").string(), TrajectoryFormat::kTum);
  eval::LoopClosureInputs loops;
  loops.candidates_examined = data_rows(out / "loop_candidates.csv");
  for (const loop::LoopRow& r : loop::read_loop_rows((out / "loops.csv").string()))
    loops.accepted.push_back({r.from_t_ns, r.to_t_ns, r.T_from_to, r.T_from_to_epnp});
  run.loops = std::move(loops);
  return run;
}

// Runs one mode like `vilslam run`, writing its folder (a failed run leaves none), or reads that folder back.
ModeRun run_mode(const fs::path& data, OfflineRunConfig config, RunMode mode, const fs::path& out, bool reuse) {
  config.mode = mode;
  if (reuse) {
    if (std::optional<ModeRun> run = read_run_folder(out, run_config_yaml(config), mode)) {
      spdlog::info("odometry-table: reusing {}", out.string());
      return *run;
    }
  }
  spdlog::info("odometry-table: {} on {}", run_mode_name(mode), data.string());
  const auto reader = open_dataset(data.string());
  OfflineRunResult result;
  try {
    Progress progress(std::string(run_mode_name(mode)) + " " + data.filename().string(), 1.0);
    result = run_offline(*reader, config, [&progress](double fraction) { progress.update(fraction); });
  } catch (const InputError&) {
    throw;
  } catch (const std::exception& e) {
    fs::remove_all(out);
    ModeRun failed;
    failed.failure = e.what();
    return failed;
  }
  write_run_outputs(out.string(), config, result);
  return outputs_of(result);
}

// MRE of the dense map of these LiDAR poses, as `vilslam map` then `vilslam eval-map --first-pose --gt`.
eval::MapRegistration map_registration(const fs::path& data, const Trajectory& T_W_L, const Trajectory& gt_T_W_L,
                                       const PointCloud& model, double voxel_m) {
  const auto start = std::chrono::steady_clock::now();
  eval::MapRegistration m;
  try {
    map::MapBuilderConfig build;
    build.voxel_size_m = voxel_m;
    PointCloud cloud;
    cloud.points = map::build_dense_map(data.string(), T_W_L, build).map.points();
    eval::MapErrorConfig config;
    config.initial = eval::first_pose_alignment(T_W_L, gt_T_W_L);
    const eval::MapError e = eval::compute_map_error(cloud, model, config);
    m.points = e.per_point_m.size();
    m.mean_m = e.mean_m;
    m.median_m = e.median_m;
    m.p95_m = e.p95_m;
    m.icp_converged = e.icp.converged;
  } catch (const InputError& e) {  // e.g. no sweep within the poses' span
    m.failure = e.what();
  } catch (const std::invalid_argument& e) {  // e.g. too few ICP correspondences
    m.failure = e.what();
  }
  m.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return m;
}

// The four dense maps of a preset (eval::MapErrors); a lost run gets none.
eval::MapErrors measure_maps(const fs::path& data, const eval::OdometryInputs& in, const eval::OdometryRow& row,
                             const Options& o) {
  const std::string model_path = open_dataset(data.string())->reference_model_path();
  if (model_path.empty()) throw InputError(data.string(), "has no reference model (model.ply) for the MRE");
  const PointCloud model = read_cloud(model_path);
  spdlog::info("odometry-table: dense maps ({} m voxels) of {}", o.map_voxel_m, row.preset);
  const auto measure = [&](const eval::RunTrajectory& run, const eval::DriftResult& drift) {
    if (drift.lost) return eval::MapRegistration{"the run is lost"};
    return map_registration(data, run.poses, in.gt_T_W_L, model, o.map_voxel_m);
  };
  eval::MapErrors maps;
  maps.voxel_m = o.map_voxel_m;
  maps.vil = measure(in.vil, row.vil);
  maps.vil_final = measure(in.vil_final, row.vil_final);
  maps.lidar_only = measure(in.lidar_only, row.lidar_only);
  maps.truth = map_registration(data, in.gt_T_W_L, in.gt_T_W_L, model, o.map_voxel_m);
  return maps;
}

eval::OdometryRow measure_preset(const fs::path& work, const std::string& preset, const OfflineRunConfig& config,
                                 const Options& o) {
  const fs::path data = work / preset;
  eval::OdometryInputs in;
  in.preset = preset;
  in.source = prepare_dataset(data, preset, o);
  in.gt_T_W_I = dataset_groundtruth(data.string(), GroundTruthFrame::kImu);
  in.gt_T_W_L = dataset_groundtruth(data.string(), GroundTruthFrame::kLidar);
  if (in.gt_T_W_I.size() < 2) throw InputError(data.string(), "has no ground truth to evaluate against");
  const ModeRun vil = run_mode(data, config, RunMode::kVil, work / (preset + "_vil"), o.reuse_runs);
  const ModeRun lidar_only =
      run_mode(data, config, RunMode::kLidarOnly, work / (preset + "_lidar-only"), o.reuse_runs);
  in.vio = {vil.camera_states, vil.failure};
  in.vil = {vil.lidar, vil.failure};
  in.vil_degenerate = vil.degenerate;
  in.vil_sweeps = vil.lidar.size();
  in.lidar_only = {lidar_only.lidar, lidar_only.failure};
  in.lidar_only_degenerate = lidar_only.degenerate;
  in.lidar_only_sweeps = lidar_only.lidar.size();
  in.vil_final = {vil.lidar_final, vil.failure};
  in.loops = vil.loops;
  eval::OdometryRow row = eval::compute_odometry_row(in);
  if (!o.no_maps) row.maps = measure_maps(data, in, row, o);
  return row;
}

// Fails early (exit 2) rather than after the runs when the table cannot be written.
void check_writable(const fs::path& out) {
  const fs::path dir = out.has_parent_path() ? out.parent_path() : fs::path(".");
  if (!fs::is_directory(dir) || ::access(dir.c_str(), W_OK) != 0)
    throw InputError(out.string(), "cannot be written: " + dir.string() + " is not a writable folder");
}

std::string format_voxel(double voxel_m) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", voxel_m);
  return buf;
}

std::string command_line(const Options& o) {
  std::string presets;
  for (const std::string& p : o.presets) presets += (presets.empty() ? "" : ",") + p;
  std::string cmd = "vilslam odometry-table --work " + o.work + " --presets " + presets + " --seed " +
                    std::to_string(o.seed) + (o.preview ? " --preview" : "") +
                    (o.ideal_sensors ? " --ideal-sensors" : "") + (o.config_path.empty() ? "" : " --config " + o.config_path) +
                    (o.no_maps ? std::string(" --no-maps") : " --map-voxel " + format_voxel(o.map_voxel_m)) +
                    (o.reuse_runs ? " --reuse-runs" : "") +
                    " --out " + o.out;
  if (!o.note.empty()) cmd += " --note '" + o.note + "'";
  return cmd;
}

std::string date_utc() {
  const std::time_t now = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&now, &tm);
  char buf[64];
  std::strftime(buf, sizeof buf, "%Y-%m-%d %H:%M UTC", &tm);
  return buf;
}

std::string machine(double load_at_start) {
  utsname u{};
  uname(&u);
  char buf[256];
  std::snprintf(buf, sizeof buf, "%s (%s, %u hardware threads, load average %.1f at the start)", u.nodename, u.machine,
                std::thread::hardware_concurrency(), load_at_start);
  return buf;
}

vilslam::cli::Command reg("odometry-table",
                          "Paper's Table I (VIO / VIL / LiDAR-only / loop-closed FDE, loops, MRE) on simulated presets",
                          [](CLI::App& app) {
  auto o = std::make_shared<Options>();
  app.add_option("--work", o->work, "Work folder: WORK/<preset> (reused or simulated), WORK/<preset>_<mode> runs")
      ->required();
  app.add_option("--presets", o->presets, "Comma-separated presets")->delimiter(',')->capture_default_str();
  app.add_option("--seed", o->seed, "Seed of the presets simulated here")->capture_default_str();
  app.add_flag("--preview", o->preview, "Simulate only the preview seconds (quick check, the route does not close)");
  app.add_flag("--ideal-sensors", o->ideal_sensors,
               "Simulate without sensor realism (`vilslam simulate --ideal-sensors`; reused folders are taken as they are)");
  app.add_option("--config", o->config_path, "Run YAML of the vil and lidar-only runs (as `vilslam run --config`)");
  auto* voxel = app.add_option("--map-voxel", o->map_voxel_m, "Voxel size of the dense maps whose MRE is measured, m")
                    ->check(CLI::PositiveNumber)
                    ->capture_default_str();
  app.add_flag("--no-maps", o->no_maps, "Do not build the dense maps (no MRE columns)")->excludes(voxel);
  app.add_flag("--reuse-runs", o->reuse_runs,
               "Read WORK/<preset>_<mode> instead of running when it holds a complete run made with this config");
  app.add_option("--out", o->out, "Markdown file to write")->capture_default_str();
  app.add_option("--note", o->note, "Text appended to the page (e.g. how reused simulations were made)");
  return [o]() {
    const auto start = std::chrono::steady_clock::now();
    double load[1] = {0};
    getloadavg(load, 1);
    for (const std::string& preset : o->presets) sim::parse_scenario(preset);
    const OfflineRunConfig config = o->config_path.empty() ? OfflineRunConfig{} : load_run_config(o->config_path);
    check_writable(o->out);
    std::error_code ec;
    fs::create_directories(o->work, ec);
    if (ec) throw InputError(o->work, "cannot create the work folder: " + ec.message());
    std::vector<eval::OdometryRow> rows;
    for (const std::string& preset : o->presets) rows.push_back(measure_preset(o->work, preset, config, *o));
    eval::OdometryDocument doc;
    doc.command = command_line(*o);
    doc.date_utc = date_utc();
    doc.machine = machine(load[0]);
    doc.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    doc.note = o->note;
    std::cout << eval::odometry_table_markdown(rows);
    write_file_atomic(o->out, eval::odometry_document_markdown(rows, doc));
    std::cout << "wrote " << o->out << "\n";
    return 0;
  };
});

}  // namespace
