// Milliseconds per 752 x 480 rendered image (and per LiDAR sweep) in each scenario, at poses along
// the route. A 60 s stereo sequence at 20 Hz is 2400 images and 600 sweeps. The counter
// process_cpu_ms is the CPU time of all threads per iteration (wall time on a shared machine says
// little; on an idle machine with n cores wall time is about process_cpu_ms / n).
#include <benchmark/benchmark.h>
#include <sys/resource.h>

#include <map>
#include <memory>

#include "sim/camera_render.h"
#include "sim/lidar_sim.h"
#include "sim/scenario_figures.h"
#include "sim/sim_config.h"

namespace {

using namespace vilslam;
using namespace vilslam::sim;

double process_cpu_s() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_utime.tv_sec + usage.ru_stime.tv_sec + 1e-6 * (usage.ru_utime.tv_usec + usage.ru_stime.tv_usec);
}

void set_cpu_counter(benchmark::State& state, double cpu_start_s) {
  state.counters["process_cpu_ms"] = 1e3 * (process_cpu_s() - cpu_start_s) / static_cast<double>(state.iterations());
}

const World& world_of(Scenario scenario) {
  static std::map<Scenario, std::unique_ptr<World>> worlds;
  auto& w = worlds[scenario];
  if (!w) w = std::make_unique<World>(World::generate(scenario, 1));
  return *w;
}

void BM_RenderImage(benchmark::State& state) {
  const auto scenario = static_cast<Scenario>(state.range(0));
  const World& world = world_of(scenario);
  const std::vector<Vec3>& route = world.route_W();
  RenderOptions options;
  render_image(world, default_camera(), [&](TimeNs) { return route_camera_pose(route, 0); }, 0, options);  // warm caches
  std::size_t k = 0;
  const double cpu_start_s = process_cpu_s();
  for (auto _ : state) {
    const SE3 T_W_C = route_camera_pose(route, (k * 7) % route.size());
    options.noise_seed = k++;
    benchmark::DoNotOptimize(render_image(world, default_camera(), [&](TimeNs) { return T_W_C; }, 0, options));
  }
  set_cpu_counter(state, cpu_start_s);
  state.SetLabel(scenario_name(scenario));
}

void BM_LidarSweep(benchmark::State& state) {
  const auto scenario = static_cast<Scenario>(state.range(0));
  const World& world = world_of(scenario);
  const std::vector<Vec3>& route = world.route_W();
  std::size_t k = 0;
  const double cpu_start_s = process_cpu_s();
  for (auto _ : state) {
    const SE3 T_W_L(Quat::Identity(), route[(k * 7) % route.size()]);
    benchmark::DoNotOptimize(simulate_sweep(world, LidarSimConfig{}, 0, [&](TimeNs) { return T_W_L; }, k++));
  }
  set_cpu_counter(state, cpu_start_s);
  state.SetLabel(scenario_name(scenario));
}

BENCHMARK(BM_RenderImage)->DenseRange(0, 5)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_LidarSweep)->DenseRange(0, 5)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
