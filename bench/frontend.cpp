// Visual frontend speed on the real EuRoC V1_01 pairs (752x480): per stereo pair, tracking and extraction.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <vector>

#include "frontend/frontend.h"
#include "io/dataset.h"

namespace {

const std::string kSequence = std::string(VILSLAM_SHARED_DATA) + "/euroc/V1_01_easy_micro";

struct Pairs {
  vilslam::RigCalibration calib;
  std::vector<vilslam::StereoFrame> frames;
};

const Pairs& euroc_pairs() {
  static const Pairs pairs = [] {
    Pairs p;
    const auto reader = vilslam::open_dataset(kSequence);
    p.calib = reader->calibration();
    while (const auto event = reader->next()) {
      if (const auto* frame = std::get_if<vilslam::StereoFrame>(&event->data)) p.frames.push_back(*frame);
    }
    return p;
  }();
  return pairs;
}

// The whole pipeline over the sequence, looping; each iteration is one stereo pair (mostly KLT tracking,
// extraction when tracks run short). Counter median_ms: the median time per pair.
void BM_FrontendSequence(benchmark::State& state) {
  if (!std::filesystem::exists(kSequence)) {
    state.SkipWithError("shared EuRoC data absent");
    return;
  }
  const Pairs& pairs = euroc_pairs();
  vilslam::Frontend frontend(pairs.calib);
  std::vector<double> ms;
  vilslam::TimeNs t_ns = 0;
  std::size_t k = 0;
  for (auto _ : state) {
    vilslam::StereoFrame frame = pairs.frames[k++ % pairs.frames.size()];
    frame.t_ns = ++t_ns;  // the loop restarts the sequence: keep time increasing
    const auto start = std::chrono::steady_clock::now();
    benchmark::DoNotOptimize(frontend.process(frame));
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    state.SetIterationTime(seconds);
    ms.push_back(seconds * 1e3);
  }
  std::nth_element(ms.begin(), ms.begin() + ms.size() / 2, ms.end());
  state.counters["median_ms"] = ms[ms.size() / 2];
}
BENCHMARK(BM_FrontendSequence)->UseManualTime()->Unit(benchmark::kMillisecond)->Iterations(950);

// The first pair of a fresh frontend: Shi-Tomasi on both images, ORB, brute-force stereo matching.
void BM_FrontendExtraction(benchmark::State& state) {
  if (!std::filesystem::exists(kSequence)) {
    state.SkipWithError("shared EuRoC data absent");
    return;
  }
  const Pairs& pairs = euroc_pairs();
  for (auto _ : state) {
    state.PauseTiming();
    vilslam::Frontend frontend(pairs.calib);
    state.ResumeTiming();
    benchmark::DoNotOptimize(frontend.process(pairs.frames.front()));
  }
}
BENCHMARK(BM_FrontendExtraction)->Unit(benchmark::kMillisecond);

}  // namespace
