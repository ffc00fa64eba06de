// Global pose graph on 1000 LiDAR poses (12.5 laps of the tests' 10 m square, biased odometry, a loop per lap):
// a batch solve from the odometry, and the re-optimization warm-started from that solution after 10 more
// poses and one more loop (how the pipeline uses it in place of the paper's iSAM2).
#include <benchmark/benchmark.h>

#include "../tests/loop/square_loop.h"

namespace {

using namespace vilslam;

constexpr std::size_t kPoses = 1000;
constexpr std::size_t kNewPoses = 10;

std::vector<loop::RelativePoseConstraint> lap_loops(const test::SquareLoop& s, std::size_t pose_count) {
  std::vector<loop::RelativePoseConstraint> loops;
  for (std::size_t v = s.lap_poses; v < pose_count; v += s.lap_poses) loops.push_back(test::true_loop(s, 0, v));
  return loops;
}

loop::PoseGraph first_graph(const test::SquareLoop& s, std::size_t pose_count) {
  loop::PoseGraph graph;
  for (std::size_t i = 0; i < pose_count; ++i) graph.add_pose(s.drifted[i].t_ns, s.drifted[i].T_W_B);
  for (std::size_t i = 0; i + 1 < pose_count; ++i) graph.add_constraint(s.odometry[i]);
  for (const auto& c : lap_loops(s, pose_count)) graph.add_constraint(c);
  return graph;
}

void BM_PoseGraphBatch(benchmark::State& state) {
  const test::SquareLoop s = test::make_square_loop(kPoses - 1 - 80);
  loop::PoseGraphSummary summary;
  for (auto _ : state) {
    loop::PoseGraph graph = first_graph(s, kPoses);
    summary = graph.optimize();
    benchmark::DoNotOptimize(graph.poses().back().T_W_B);
  }
  state.counters["iterations"] = summary.iterations;
  state.counters["loops"] = static_cast<double>(summary.loop.count);
}
BENCHMARK(BM_PoseGraphBatch)->Unit(benchmark::kMillisecond);

void BM_PoseGraphWarmStartedReoptimize(benchmark::State& state) {
  const test::SquareLoop s = test::make_square_loop(kPoses - 1 - 80);
  const std::size_t first = kPoses - kNewPoses;
  loop::PoseGraph solved = first_graph(s, first);
  solved.optimize();
  loop::PoseGraphSummary summary;
  for (auto _ : state) {
    state.PauseTiming();
    loop::PoseGraph graph = solved;
    // New poses continue the corrected trajectory with the odometry increments.
    for (std::size_t i = first; i < kPoses; ++i) {
      graph.add_pose(s.drifted[i].t_ns, graph.poses().back().T_W_B * s.odometry[i - 1].T_from_to);
      graph.add_constraint(s.odometry[i - 1]);
    }
    graph.add_constraint(test::true_loop(s, (kPoses - 1) % s.lap_poses, kPoses - 1));
    state.ResumeTiming();
    summary = graph.optimize();
    benchmark::DoNotOptimize(graph.poses().back().T_W_B);
  }
  state.counters["iterations"] = summary.iterations;
}
BENCHMARK(BM_PoseGraphWarmStartedReoptimize)->Unit(benchmark::kMillisecond);

}  // namespace
