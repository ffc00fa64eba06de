// LiDAR mapping cost per sweep for each simulated sensor model (docs/simulator.md) at the same place of
// the highbay: feature extraction of the new sweep (rings for the VLP-16 and the 128-beam sensor, point
// neighbourhoods for the non-repetitive one) plus its scan-to-map registration against the previous
// sweep's features, from the previous pose (the walking motion of 0.1 s left to the registration), with each
// sensor's run config (config/run_<sensor>.yaml).
// Run: ./build/bin/bench_lidar_sensors --benchmark_repetitions=10 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <memory>
#include <string>

#include "lidar/features.h"
#include "lidar/lidar_config.h"
#include "pipeline/run_config.h"
#include "sim/lidar_sim.h"
#include "sim/sim_config.h"
#include "sim/trajectory.h"
#include "sim/world.h"

namespace {

using namespace vilslam;

const char* const kSensors[] = {"vlp16", "hesai128", "mid360"};

struct Case {
  LidarScan previous, current;
  SE3 T_W_L_previous;
};

const Case& load_case(int sensor) {
  static std::unique_ptr<Case> cases[3];
  if (!cases[sensor]) {
    static const sim::World world = sim::World::generate(sim::Scenario::kHighbay, 3);
    const sim::RouteMotion motion(world.route_W(), sim::route_motion_config(sim::SimConfig{}, sim::Scenario::kHighbay));
    const SE3 T_I_L = sim::rig_calibration(sim::SimConfig{}).T_I_L;
    const auto T_W_L = [&](TimeNs t) { return motion.pose(t) * T_I_L; };
    sim::LidarSimConfig config = sim::lidar_sensor(kSensors[sensor]);
    config.returns = sim::ideal_returns();  // the sweeps of `vilslam simulate` without sensor realism
    auto c = std::make_unique<Case>();
    const TimeNs t0 = 10'000'000'000, period = 100'000'000;
    c->previous = sim::simulate_sweep(world, config, t0, T_W_L, 1);
    c->current = sim::simulate_sweep(world, config, t0 + period, T_W_L, 2);
    c->T_W_L_previous = T_W_L(t0 + period);
    cases[sensor] = std::move(c);
  }
  return *cases[sensor];
}

void BM_SensorExtractAndRegister(benchmark::State& state) {
  const Case& c = load_case(static_cast<int>(state.range(0)));
  const std::string sensor = kSensors[state.range(0)];
  const lidar::LidarConfig config = load_run_config(VILSLAM_SOURCE_DIR "/config/run_" + sensor + ".yaml").lidar.lidar;
  const lidar::FeatureConfig feature_config = lidar::features_for_registration(config);
  lidar::FeatureMap map(config.map);
  map.insert(lidar::extract_features(c.previous, config.rings, feature_config), c.T_W_L_previous);
  lidar::RegistrationResult result;
  std::size_t features = 0;
  for (auto _ : state) {
    const lidar::FeatureScan f = lidar::extract_features(c.current, config.rings, feature_config);
    result = lidar::register_scan(f, map, c.T_W_L_previous, config.registration);
    features = f.edges.size() + f.surfaces.size();
    benchmark::DoNotOptimize(result);
  }
  state.SetLabel(sensor);
  state.counters["points"] = static_cast<double>(c.current.points.size());
  state.counters["features"] = static_cast<double>(features);
}

// Argument: 0 VLP-16, 1 hesai128 (128 beams), 2 mid360 (non-repetitive).
BENCHMARK(BM_SensorExtractAndRegister)->Arg(0)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->MeasureProcessCPUTime();

}  // namespace
