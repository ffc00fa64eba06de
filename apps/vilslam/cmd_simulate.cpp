#include <iostream>

#include "common/progress.h"
#include "common/error.h"
#include "sim/simulator.h"
#include "vilslam/command.h"

namespace {

struct Options {
  std::string scenario;
  std::string out;
  std::uint64_t seed = 0;
  std::uint64_t world_seed = 0;
  double route_start = 0;
  double route_offset_m = 0;
  double length_m = 0;
  double duration_s = 0;
  int laps = 1;
  bool preview = false;
  std::string config;
  std::string trajectory;
  std::string imu;
  bool report = false;
  bool ideal_sensors = false;
  bool overwrite = false;
  std::string lidar;
};

vilslam::cli::Command reg("simulate", "Simulate a scenario as a stereo + IMU + LiDAR dataset with ground truth",
                          [](CLI::App& app) {
  auto o = std::make_shared<Options>();
  app.add_option("scenario", o->scenario, "highbay | hallway | tunnel | loop | outdoor | room")
      ->required()
      ->check(CLI::IsMember({"highbay", "hallway", "tunnel", "loop", "outdoor", "room"}));
  app.add_option("--out", o->out, "Output dataset folder")->required();
  app.add_option("--seed", o->seed, "Random seed (world, noise)")->capture_default_str();
  auto* world_seed = app.add_option("--world-seed", o->world_seed,
                                    "Build the world from this seed instead (the same world, other noise)");
  auto* route_start = app.add_option("--route-start", o->route_start,
                                     "Start this fraction of the route's length along it (another start pose)")
                          ->check(CLI::Range(0.0, 0.999));
  auto* route_offset = app.add_option("--route-offset", o->route_offset_m,
                                      "Fly the route shifted sideways by this many metres (left of travel when positive)")
                           ->check(CLI::Range(-2.0, 2.0));
  auto* length = app.add_option("--length", o->length_m, "Route length in metres (default: the paper's)")
                     ->check(CLI::PositiveNumber);
  auto* duration = app.add_option("--duration", o->duration_s,
                                  "Size the route so the sequence lasts this many seconds (with --trajectory: fly its "
                                  "first seconds)")
                       ->check(CLI::PositiveNumber)
                       ->excludes(length);
  auto* laps = app.add_option("--laps", o->laps, "Fly the route this many times (same world, longer sequence)")
                   ->check(CLI::Range(1, 100))
                   ->excludes(duration)
                   ->capture_default_str();
  app.add_flag("--preview", o->preview, "Only the first seconds (config preview_duration_s), coarse model");
  app.add_option("--config", o->config, "Simulator YAML (config/sim_default.yaml)")->check(CLI::ExistingFile);
  auto* trajectory = app.add_option("--trajectory", o->trajectory, "Fly this ground truth (TUM) in the room")
                         ->check(CLI::ExistingFile);
  app.add_option("--imu", o->imu, "Use this real IMU stream (EuRoC imu0/data.csv) and its timestamps")
      ->check(CLI::ExistingFile)
      ->needs(trajectory);
  app.add_option("--lidar", o->lidar, "LiDAR model, replacing the config's lidar section (docs/simulator.md)")
      ->check(CLI::IsMember({"vlp16", "hesai128", "mid360"}));
  app.add_flag("--ideal-sensors", o->ideal_sensors,
               "No calibration errors, missed LiDAR echoes, mixed pixels or vignetting (docs/simulator.md)");
  app.add_flag("--report", o->report, "Print a table of the sequence and write DIR/report.json");
  app.add_flag("--overwrite", o->overwrite, "Replace an existing output folder");
  return [o, world_seed, route_start, route_offset, laps]() {
    using namespace vilslam::sim;
    SimConfig config = o->config.empty() ? SimConfig{} : load_sim_config(o->config);
    if (!o->lidar.empty()) config.lidar = lidar_sensor(o->lidar);
    if (o->ideal_sensors) config.sensor_realism = false;
    SimulateRequest request;
    request.scenario = parse_scenario(o->scenario);
    if (!o->trajectory.empty() && request.scenario != Scenario::kRoom)
      throw vilslam::InputError(o->trajectory, "--trajectory flies recorded motion in the 'room' scenario only");
    if (!o->trajectory.empty() && (route_start->count() > 0 || route_offset->count() > 0 || laps->count() > 0))
      throw vilslam::InputError(o->trajectory,
                                "--route-start, --route-offset and --laps vary the world's route, not a --trajectory");
    request.out_dir = o->out;
    request.seed = o->seed;
    if (world_seed->count() > 0) request.world_seed = o->world_seed;
    request.route_start = o->route_start;
    request.route_offset_m = o->route_offset_m;
    request.length_m = o->length_m;
    request.duration_s = o->duration_s;
    request.laps = o->laps;
    request.preview = o->preview;
    request.trajectory_path = o->trajectory;
    request.imu_path = o->imu;
    request.overwrite = o->overwrite;
    request.report = o->report;
    SequenceReport report;
    {
      vilslam::Progress progress("simulate " + o->scenario, 1.0);
      request.progress = [&progress](double fraction) { progress.update(fraction); };
      report = simulate(config, request);
    }
    std::cout << "wrote " << o->out << ": " << report.stereo_frames << " stereo frames, " << report.imu_samples
              << " IMU samples, " << report.lidar_scans << " LiDAR scans\n";
    if (o->report) {
      std::cout << report_table({report});
      write_report_json(o->out + "/report.json", {report});
    }
    return 0;
  };
});

}  // namespace
