// Dataset reading speed on the shared EuRoC V1_01_easy_micro: indexing (calibration, IMU and
// ground-truth csv, image listing) and streaming every event with its PNGs decoded.
#include <benchmark/benchmark.h>

#include <spdlog/spdlog.h>

#include <filesystem>

#include "io/dataset.h"

namespace {

// The four skipped cam1 rows would log a warning on every open.
std::string v1_01() {
  spdlog::set_level(spdlog::level::err);
  const std::string path = std::string(VILSLAM_SHARED_DATA) + "/euroc/V1_01_easy_micro";
  return std::filesystem::exists(path) ? path : std::string();
}

void BM_OpenEuroc(benchmark::State& state) {
  const std::string root = v1_01();
  if (root.empty()) return state.SkipWithError("shared data absent");
  for (auto _ : state) benchmark::DoNotOptimize(vilslam::open_dataset(root));
}
BENCHMARK(BM_OpenEuroc)->Unit(benchmark::kMillisecond);

void BM_StreamEuroc(benchmark::State& state) {
  const std::string root = v1_01();
  if (root.empty()) return state.SkipWithError("shared data absent");
  const auto reader = vilslam::open_dataset(root);
  std::size_t events = 0;
  for (auto _ : state) {
    reader->rewind();
    while (auto e = reader->next()) ++events;
  }
  state.counters["events"] = benchmark::Counter(static_cast<double>(events), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_StreamEuroc)->Unit(benchmark::kMillisecond);

}  // namespace
