// Visual frontend speed on the real EuRoC V1_01 pairs (752x480): whole pipeline per stereo pair, and stages.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <vector>

#include "frontend/corner_extractor.h"
#include "frontend/frontend.h"
#include "frontend/klt_tracker.h"
#include "frontend/vignetting.h"
#include "io/dataset.h"

namespace {

const std::string kSequence = std::string(VILSLAM_SHARED_DATA) + "/euroc/V1_01_easy_micro";

struct Pairs {
  vilslam::RigCalibration calib;
  std::vector<vilslam::StereoFrame> frames;
};

// The sequence's stereo pairs, loaded once; nullptr (and the benchmark skipped) when the data is absent.
const Pairs* euroc_pairs(benchmark::State& state) {
  if (!std::filesystem::exists(kSequence)) {
    state.SkipWithError("shared EuRoC data absent");
    return nullptr;
  }
  static const Pairs pairs = [] {
    Pairs p;
    const auto reader = vilslam::open_dataset(kSequence);
    p.calib = reader->calibration();
    while (const auto event = reader->next()) {
      if (const auto* frame = std::get_if<vilslam::StereoFrame>(&event->data)) p.frames.push_back(*frame);
    }
    return p;
  }();
  return &pairs;
}

// The whole pipeline over the sequence, looping; each iteration is one stereo pair (mostly KLT tracking,
// extraction when tracks run short and after each restart). Counter median_ms: the median time per pair.
// Argument 1: the default config; 0: the same without the vignetting self-calibration (vignetting_samples 0);
// 3: the default without its 11 px final KLT window (klt_final_window_px 0). (2 was the anchored tracks, removed
// on 2026-12-08: docs/removed_options.md.)
void BM_FrontendSequence(benchmark::State& state) {
  const Pairs* pairs = euroc_pairs(state);
  if (!pairs) return;
  vilslam::FrontendConfig config;
  if (state.range(0) == 0) config.vignetting_samples = 0;
  if (state.range(0) == 3) config.klt_final_window_px = 0;
  vilslam::Frontend frontend(pairs->calib, config);
  std::vector<double> ms;
  vilslam::TimeNs t_ns = 0;
  std::size_t k = 0;
  for (auto _ : state) {
    vilslam::StereoFrame frame = pairs->frames[k++ % pairs->frames.size()];
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
BENCHMARK(BM_FrontendSequence)->Arg(1)->Arg(0)->Arg(3)->UseManualTime()->Unit(benchmark::kMillisecond)->Iterations(950);

// The first pair of a fresh frontend: Shi-Tomasi on both images, ORB, stereo matching, refinement.
void BM_FrontendExtraction(benchmark::State& state) {
  const Pairs* pairs = euroc_pairs(state);
  if (!pairs) return;
  for (auto _ : state) {
    state.PauseTiming();
    vilslam::Frontend frontend(pairs->calib);
    state.ResumeTiming();
    benchmark::DoNotOptimize(frontend.process(pairs->frames.front()));
  }
}
BENCHMARK(BM_FrontendExtraction)->Unit(benchmark::kMillisecond);

// The first 200 Shi-Tomasi corners of the first left image (the tracks of the stage benchmarks).
std::vector<cv::Point2f> first_corners(const Pairs& pairs, const vilslam::FrontendConfig& config) {
  std::vector<cv::Point2f> corners = vilslam::detect_corners(pairs.frames[0].left, config);
  corners.resize(std::min<std::size_t>(corners.size(), 200));
  return corners;
}

// Stages, for the cost breakdown in docs/frontend.md.
void BM_StagePyramidsBothImages(benchmark::State& state) {
  const Pairs* pairs = euroc_pairs(state);
  if (!pairs) return;
  const vilslam::FrontendConfig config;
  for (auto _ : state) {
    benchmark::DoNotOptimize(vilslam::build_klt_pyramid(pairs->frames[1].left, config));
    benchmark::DoNotOptimize(vilslam::build_klt_pyramid(pairs->frames[1].right, config));
  }
}
BENCHMARK(BM_StagePyramidsBothImages)->Unit(benchmark::kMillisecond);

// Forward-backward KLT of 200 corners between two left images, run twice (as for the left and right tracks).
// Argument: the KLT window size.
void BM_StageKltBothImages(benchmark::State& state) {
  const Pairs* pairs = euroc_pairs(state);
  if (!pairs) return;
  vilslam::FrontendConfig config;
  config.klt_window_px = static_cast<int>(state.range(0));
  const std::vector<cv::Point2f> corners = first_corners(*pairs, config);
  const vilslam::ImagePyramid prev = vilslam::build_klt_pyramid(pairs->frames[0].left, config);
  const vilslam::ImagePyramid cur = vilslam::build_klt_pyramid(pairs->frames[1].left, config);
  std::vector<cv::Point2f> tracked_px;
  std::vector<bool> tracked;
  for (auto _ : state) {
    for (int image = 0; image < 2; ++image) vilslam::track_klt(prev, cur, corners, config, &tracked_px, &tracked);
  }
}
BENCHMARK(BM_StageKltBothImages)->Arg(21)->Arg(15)->Unit(benchmark::kMillisecond);

void BM_StageShiTomasiBothImages(benchmark::State& state) {
  const Pairs* pairs = euroc_pairs(state);
  if (!pairs) return;
  const vilslam::FrontendConfig config;
  for (auto _ : state) {
    benchmark::DoNotOptimize(vilslam::detect_corners(pairs->frames[0].left, config));
    benchmark::DoNotOptimize(vilslam::detect_corners(pairs->frames[0].right, config));
  }
}
BENCHMARK(BM_StageShiTomasiBothImages)->Unit(benchmark::kMillisecond);

// The vignetting self-calibration's costs (FrontendConfig::vignetting_samples, docs/frontend.md): once fitted,
// dividing both images by the falloff (every pair); while collecting, the brightness samples of 200 tracks in
// both images (the corners against themselves in the next pair).
void BM_StageDevignetteBothImages(benchmark::State& state) {
  const Pairs* pairs = euroc_pairs(state);
  if (!pairs) return;
  vilslam::VignettingModel model = vilslam::VignettingModel::flat(pairs->calib.cam0);
  model.k = Eigen::Vector3d(-0.96, 0.77, -0.28);  // the simulator's falloff (vignetting 0.5)
  const cv::Mat gain = vilslam::devignetting_gain(model, pairs->frames[1].left.size());
  for (auto _ : state) {
    benchmark::DoNotOptimize(vilslam::devignette(pairs->frames[1].left, gain));
    benchmark::DoNotOptimize(vilslam::devignette(pairs->frames[1].right, gain));
  }
}
BENCHMARK(BM_StageDevignetteBothImages)->Unit(benchmark::kMillisecond);

void BM_StageVignettingSamplesBothImages(benchmark::State& state) {
  const Pairs* pairs = euroc_pairs(state);
  if (!pairs) return;
  const vilslam::FrontendConfig config;
  const std::vector<cv::Point2f> corners = first_corners(*pairs, config);
  const std::vector<bool> tracked(corners.size(), true);
  for (auto _ : state) {
    vilslam::VignettingEstimator estimator(pairs->calib.cam0);
    for (int image = 0; image < 2; ++image) {
      estimator.add_step(pairs->frames[0].left, pairs->frames[1].left, corners, corners, tracked);
    }
    benchmark::DoNotOptimize(estimator.informative_samples());
  }
}
BENCHMARK(BM_StageVignettingSamplesBothImages)->Unit(benchmark::kMillisecond);

}  // namespace
