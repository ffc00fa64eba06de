// Cost of one fixed-lag smoother step (solve + marginalization) with a full window, on the analytic
// motion and ring of landmarks of the VIO unit tests. Arguments: window size, landmarks in the ring
// (1200 give about 200 stereo matches a frame, what the frontend keeps on the simulated presets).
#include <benchmark/benchmark.h>

#include <random>

#include "../tests/vio/analytic_motion.h"
#include "vio/smoother.h"

namespace vilslam {
namespace {

struct FrameData {
  Preintegration preint;
  FrontendOutput frame;
};

void BM_SmootherStep(benchmark::State& bench) {
  const int window = static_cast<int>(bench.range(0));
  const test::AnalyticMotion motion;
  const StereoExtrinsics extr = test::test_extrinsics();
  const std::vector<Vec3> landmarks = test::test_landmarks(static_cast<int>(bench.range(1)), 1);
  std::mt19937 rng(1);
  const ImuNoise noise;
  const double focal_px = 450.0, frame_dt = 0.1;
  SmootherConfig config;
  config.window_size = window;
  const int frames = window + 30;

  // Exact IMU integrated per frame interval (the cost measured is the smoother's, not the data's).
  std::vector<ImuSample> imu;
  for (int k = 0; k <= frames * 20 + 1; ++k) imu.push_back(motion.imu(0.5 + 0.005 * k));
  std::vector<FrameData> data;
  for (int k = 1; k <= frames; ++k) {
    Preintegration p(Vec3::Zero(), Vec3::Zero(), noise);
    integrate_samples(imu, s_to_ns(0.5 + frame_dt * (k - 1)), s_to_ns(0.5 + frame_dt * k), p);
    data.push_back({p, test::observe(motion.state(0.5 + frame_dt * k), landmarks, extr, 0.5 / focal_px, rng)});
  }
  Vec15 sigma = Vec15::Constant(1e-3);
  double matches = 0;
  for (auto _ : bench) {
    bench.PauseTiming();
    Smoother smoother(config, extr, noise, focal_px);
    const NavState x0 = motion.state(0.5);
    smoother.initialize(x0, sigma, test::observe(x0, landmarks, extr, 0.5 / focal_px, rng));
    for (int k = 0; k < window; ++k) smoother.add_frame(data[k].preint, data[k].frame);
    bench.ResumeTiming();
    for (int k = window; k < frames; ++k) {
      smoother.add_frame(data[k].preint, data[k].frame);
      matches += static_cast<double>(data[k].frame.matches.size());
    }
  }
  bench.SetItemsProcessed(bench.iterations() * (frames - window));
  bench.counters["matches_per_frame"] = matches / static_cast<double>(bench.iterations() * (frames - window));
}
BENCHMARK(BM_SmootherStep)->Args({5, 1200})->Args({10, 400})->Args({10, 1200})->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace vilslam
