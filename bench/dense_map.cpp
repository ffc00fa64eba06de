// DenseMap at 1 cm on a surface-like cloud, as a LiDAR map is: points on the floor and four walls of a
// 20 m x 20 m x 5 m hall, offset along the surface normal by Gaussian noise (sigma 1 cm).
// Counters: voxels and memory_bytes() per voxel after all points are inserted.
#include <benchmark/benchmark.h>

#include <random>
#include <vector>

#include "map/dense_map.h"

namespace {

using Eigen::Vector3f;

std::vector<Vector3f> hall_points_W(std::size_t count) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  std::normal_distribution<float> noise_m(0.0f, 0.01f);
  constexpr float kSide_m = 20.0f, kHeight_m = 5.0f;
  std::vector<Vector3f> points_W;
  points_W.reserve(count);
  for (std::size_t i = 0; i < count; ++i) {
    const float a = u(rng), b = u(rng), n = noise_m(rng);
    switch (i % 5) {
      case 0: points_W.emplace_back(a * kSide_m, b * kSide_m, n); break;  // floor
      case 1: points_W.emplace_back(n, a * kSide_m, b * kHeight_m); break;
      case 2: points_W.emplace_back(kSide_m + n, a * kSide_m, b * kHeight_m); break;
      case 3: points_W.emplace_back(a * kSide_m, n, b * kHeight_m); break;
      default: points_W.emplace_back(a * kSide_m, kSide_m + n, b * kHeight_m); break;
    }
  }
  return points_W;
}

void BM_DenseMapInsertHall(benchmark::State& state) {
  const std::vector<Vector3f> points_W = hall_points_W(static_cast<std::size_t>(state.range(0)));
  std::size_t voxels = 0, bytes = 0;
  for (auto _ : state) {
    vilslam::map::DenseMap map(0.01);
    map.insert(points_W);
    voxels = map.num_voxels();
    bytes = map.memory_bytes();
    benchmark::DoNotOptimize(voxels);
  }
  state.counters["voxels"] = static_cast<double>(voxels);
  state.counters["bytes_per_voxel"] = static_cast<double>(bytes) / static_cast<double>(voxels);
  state.counters["points_per_s"] = benchmark::Counter(static_cast<double>(points_W.size()), benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(BM_DenseMapInsertHall)->Arg(1'000'000)->Arg(4'000'000)->Unit(benchmark::kMillisecond);

}  // namespace
