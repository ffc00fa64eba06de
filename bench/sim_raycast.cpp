// Rays per second of World::raycast in every scenario, for camera-like ray bundles (a 90 deg pinhole
// fan looking along the route) and for full VLP-16 sweeps. The camera renderer's budget is about
// 0.25 us per ray (4 M rays/s) on one core. Also the size and cost of the reference model.
#include <benchmark/benchmark.h>

#include <cmath>
#include <vector>

#include "sim/lidar_sim.h"
#include "sim/world.h"

namespace {

using vilslam::SE3;
using vilslam::Vec3;
using vilslam::sim::Scenario;
using vilslam::sim::World;

struct Rays {
  std::vector<Vec3> origins, dirs;
};

// A 160 x 100 pinhole fan (90 deg horizontal) at every 10th waypoint, looking along the route.
Rays camera_rays(const World& world) {
  Rays rays;
  const auto& route = world.route_W();
  for (std::size_t i = 0; i + 1 < route.size(); i += 10) {
    const Vec3 forward = (route[i + 1] - route[i]).normalized();
    const Vec3 left = Vec3::UnitZ().cross(forward).normalized(), up = forward.cross(left);
    for (int v = 0; v < 100; ++v) {
      for (int u = 0; u < 160; ++u) {
        const double x = (u - 79.5) / 80.0, y = (v - 49.5) / 80.0;
        rays.origins.push_back(route[i]);
        rays.dirs.push_back((forward - x * left - y * up).normalized());
      }
    }
  }
  return rays;
}

void BM_CameraRays(benchmark::State& state) {
  const World world = World::generate(static_cast<Scenario>(state.range(0)), 1);
  const Rays rays = camera_rays(world);
  std::size_t i = 0, hits = 0;
  for (auto _ : state) {
    const auto hit = world.raycast(rays.origins[i], rays.dirs[i], 100.0);
    hits += hit.has_value();
    benchmark::DoNotOptimize(hit);
    if (++i == rays.dirs.size()) i = 0;
  }
  state.SetItemsProcessed(state.iterations());
  state.SetLabel(vilslam::sim::scenario_name(world.scenario()));
  state.counters["hit_fraction"] = static_cast<double>(hits) / static_cast<double>(state.iterations());
}

void BM_LidarSweep(benchmark::State& state) {
  const World world = World::generate(static_cast<Scenario>(state.range(0)), 1);
  const vilslam::sim::LidarSimConfig config;
  const SE3 pose(vilslam::Quat::Identity(), world.route_W()[world.route_W().size() / 3]);
  std::uint64_t seed = 0;
  for (auto _ : state) {
    const auto scan = vilslam::sim::simulate_sweep(world, config, 0, [&](vilslam::TimeNs) { return pose; }, seed++);
    benchmark::DoNotOptimize(scan.points.data());
  }
  state.SetItemsProcessed(state.iterations() * config.num_rings * 1800);  // rays cast per sweep
  state.SetLabel(vilslam::sim::scenario_name(world.scenario()));
}

// The reference model: surface samples 0.1 m apart (points and time per world).
void BM_SampleSurfaces(benchmark::State& state) {
  const World world = World::generate(static_cast<Scenario>(state.range(0)), 1);
  std::size_t points = 0;
  for (auto _ : state) points = world.sample_surfaces(0.1).size();
  state.counters["points"] = static_cast<double>(points);
  state.SetLabel(vilslam::sim::scenario_name(world.scenario()));
}

void scenarios(benchmark::internal::Benchmark* b) {
  for (int s = 0; s <= static_cast<int>(Scenario::kRoom); ++s) b->Arg(s);
}

BENCHMARK(BM_CameraRays)->Apply(scenarios);
BENCHMARK(BM_LidarSweep)->Apply(scenarios)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_SampleSurfaces)->Apply(scenarios)->Unit(benchmark::kMillisecond)->Iterations(1);

}  // namespace
