// The dense map's mixed-pixel filter (lidar/mixed_pixels.h) on one simulated sweep of the highbay, with the
// simulator's sensor realism (mixed pixels at depth edges): along the rings of a VLP-16 sweep, and by direction
// (a k-d tree over the beams) on a Mid-360-style sweep without rings. Counter: the sweep's points.
// Run: ./build/bin/bench_mixed_pixels --benchmark_repetitions=10 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <algorithm>
#include <memory>
#include <vector>

#include "lidar/mixed_pixels.h"
#include "sim/lidar_sim.h"
#include "sim/sim_config.h"
#include "sim/trajectory.h"
#include "sim/world.h"

namespace {

using namespace vilslam;

const char* const kSensors[] = {"vlp16", "mid360"};

const LidarScan& sweep(int sensor) {
  static std::unique_ptr<LidarScan> sweeps[2];
  if (!sweeps[sensor]) {
    const sim::World world = sim::World::generate(sim::Scenario::kHighbay, 3);
    const sim::RouteMotion motion(world.route_W(), sim::route_motion_config(sim::SimConfig{}, sim::Scenario::kHighbay));
    const SE3 T_I_L = sim::rig_calibration(sim::SimConfig{}).T_I_L;
    const auto T_W_L = [&](TimeNs t) { return motion.pose(t) * T_I_L; };
    sweeps[sensor] = std::make_unique<LidarScan>(
        sim::simulate_sweep(world, sim::lidar_sensor(kSensors[sensor]), 10'000'000'000, T_W_L, 1));
  }
  return *sweeps[sensor];
}

void BM_MixedPixels(benchmark::State& state) {
  const LidarScan& scan = sweep(static_cast<int>(state.range(0)));
  std::size_t flagged = 0;
  for (auto _ : state) {
    const std::vector<bool> mixed = lidar::mixed_pixels(scan);
    flagged = static_cast<std::size_t>(std::count(mixed.begin(), mixed.end(), true));
    benchmark::DoNotOptimize(flagged);
  }
  state.SetLabel(kSensors[state.range(0)]);
  state.counters["points"] = static_cast<double>(scan.points.size());
  state.counters["flagged"] = static_cast<double>(flagged);
}
BENCHMARK(BM_MixedPixels)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

}  // namespace
