// One loop correction of the running system's global pose graph at 1,000 / 5,000 / 20,000 LiDAR poses
// (tests/loop/block_route.h: laps of 500 poses around a block, ~1 % odometry drift, a loop a lap): the graph
// is built and corrected loop by loop as the system would, then the timed part adds one new loop at the last
// pose and calls optimize(). Three cases: the loop to the previous lap (the usual one), the loop to the first
// lap (the whole graph moves), and the batch PoseGraph with every pose re-optimized warm-started after the
// same new loop (what the bounded correction replaces; its counter diff_mm is the largest position difference
// between the two corrected trajectories). Each at the default loop loss scale (1 sigma) and at 3.5 sigmas.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cstdint>
#include <map>
#include <utility>

#include "../tests/loop/block_route.h"
#include "loop/global_pose_graph.h"

namespace {

using namespace vilslam;

struct Setup {
  test::BlockRoute route;
  loop::GlobalPoseGraph graph;  // every loop before the last pose added and corrected
};

// Benchmark arguments: the pose count and the loop loss scale in tenths of a sigma (10: the default 1 sigma).
loop::GlobalPoseGraphConfig route_config(std::int64_t loss_scale_tenths) {
  loop::GlobalPoseGraphConfig config;
  config.odometry_sigma_m = test::kRouteOdometrySigmaM;
  config.odometry_sigma_rad = test::kRouteOdometrySigmaRad;
  config.loop_loss_scale = 0.1 * static_cast<double>(loss_scale_tenths);
  return config;
}

const Setup& setup(const benchmark::State& state) {
  static std::map<std::pair<std::int64_t, std::int64_t>, Setup> cache;
  const auto key = std::make_pair(state.range(0), state.range(1));
  auto it = cache.find(key);
  if (it != cache.end()) return it->second;
  const auto pose_count = static_cast<std::size_t>(state.range(0));
  Setup s{test::make_block_route(pose_count), loop::GlobalPoseGraph(route_config(state.range(1)))};
  s.graph.add_first_pose(s.route.truth[0].t_ns, s.route.truth[0].T_W_B);
  std::size_t next_loop = 0;
  for (std::size_t i = 1; i < pose_count; ++i) {
    s.graph.add_odometry(s.route.truth[i].t_ns, s.route.odometry[i]);
    for (; next_loop < s.route.loops.size() && s.route.loops[next_loop].to_index == i; ++next_loop) {
      const loop::RelativePoseConstraint& c = s.route.loops[next_loop];
      if (c.to_index == pose_count - 1) continue;  // the last pose gets the benchmark's loop
      s.graph.add_loop(c.from_index, c.to_index, c.T_from_to, c.information);
      s.graph.optimize();
    }
  }
  return cache.emplace(key, std::move(s)).first->second;
}

// The new loop: the last pose seen again from `u`, measured from the truth.
loop::RelativePoseConstraint new_loop(const test::BlockRoute& r, std::size_t u) {
  const std::size_t v = r.truth.size() - 1;
  return {u, v, r.truth[u].T_W_B.inverse() * r.truth[v].T_W_B,
          loop::information_from_sigmas(test::kRouteLoopSigmaM, test::kRouteLoopSigmaRad), loop::ConstraintKind::kLoop};
}

void time_correction(benchmark::State& state, const Setup& s, const loop::RelativePoseConstraint& c) {
  loop::CorrectionSummary summary;
  for (auto _ : state) {
    state.PauseTiming();
    loop::GlobalPoseGraph graph = s.graph;
    graph.add_loop(c.from_index, c.to_index, c.T_from_to, c.information);
    state.ResumeTiming();
    summary = graph.optimize();
    benchmark::DoNotOptimize(graph.pose(graph.size() - 1));
  }
  state.counters["variables"] = static_cast<double>(summary.variables);
  state.counters["moved_poses"] = static_cast<double>(summary.moved_poses);
  state.counters["iterations"] = summary.iterations;
}

void BM_GlobalCorrectionPreviousLap(benchmark::State& state) {
  const Setup& s = setup(state);
  time_correction(state, s, new_loop(s.route, s.route.truth.size() - 1 - s.route.lap_poses));
}
BENCHMARK(BM_GlobalCorrectionPreviousLap)
    ->ArgsProduct({{1000, 5000, 20000}, {10, 35}})
    ->Unit(benchmark::kMillisecond);

void BM_GlobalCorrectionFirstLap(benchmark::State& state) {
  const Setup& s = setup(state);
  time_correction(state, s, new_loop(s.route, (s.route.truth.size() - 1) % s.route.lap_poses));
}
BENCHMARK(BM_GlobalCorrectionFirstLap)
    ->ArgsProduct({{1000, 5000, 20000}, {10, 35}})
    ->Unit(benchmark::kMillisecond);

void BM_BatchCorrectionPreviousLap(benchmark::State& state) {
  const Setup& s = setup(state);
  const test::BlockRoute& r = s.route;
  const loop::RelativePoseConstraint c = new_loop(r, r.truth.size() - 1 - r.lap_poses);
  // The batch graph of the same factors, at its own solution before the new loop.
  loop::PoseGraph solved;
  for (const TimedPose& p : s.graph.trajectory()) solved.add_pose(p.t_ns, p.T_W_B);
  const Mat6 odometry_information =
      loop::information_from_sigmas(test::kRouteOdometrySigmaM, test::kRouteOdometrySigmaRad);
  for (std::size_t i = 1; i < r.truth.size(); ++i) {
    solved.add_constraint({i - 1, i, r.odometry[i], odometry_information, loop::ConstraintKind::kOdometry});
  }
  for (const auto& l : r.loops) {
    if (l.to_index != r.truth.size() - 1) solved.add_constraint(l);
  }
  loop::PoseGraphOptions options;
  options.loop_loss_scale = 0.1 * static_cast<double>(state.range(1));
  solved.optimize(options);
  loop::PoseGraphSummary summary;
  loop::PoseGraph graph;
  for (auto _ : state) {
    state.PauseTiming();
    graph = solved;
    graph.add_constraint(c);
    state.ResumeTiming();
    summary = graph.optimize(options);
    benchmark::DoNotOptimize(graph.poses().back().T_W_B);
  }
  loop::GlobalPoseGraph global = s.graph;
  global.add_loop(c.from_index, c.to_index, c.T_from_to, c.information);
  global.optimize();
  double diff_m = 0.0;
  for (std::size_t i = 0; i < r.truth.size(); ++i) {
    diff_m = std::max(diff_m, (global.pose(i).translation() - graph.poses()[i].T_W_B.translation()).norm());
  }
  state.counters["variables"] = static_cast<double>(r.truth.size() - 1);
  state.counters["iterations"] = summary.iterations;
  state.counters["diff_mm"] = 1e3 * diff_m;
}
BENCHMARK(BM_BatchCorrectionPreviousLap)
    ->ArgsProduct({{1000, 5000, 20000}, {10, 35}})
    ->Unit(benchmark::kMillisecond);

}  // namespace
