// Loop closure speed: one BoW database query at 1,000 / 5,000 key frames, one loop constraint of a true
// revisit (descriptor matching, EPnP RANSAC, ICP, checks) and its EPnP step alone, and one key frame of a run
// re-localizing in a saved map of 1,000 / 5,000 key frames (docs/loop.md, "Map reuse").
// BoW entries: the left image rendered at 50 poses evenly spread in time along the simulated highbay route
// (seed 1), described by the frontend's ORB and the shipped vocabulary; key frame i keeps a random 80 % of
// image i mod 50's descriptors (std::mt19937_64, seed 1), so entries differ as a long run's key frames do.
// The constraint: test_loop_closer.cpp's A -> B (the same place from 1.5 m further and 15 deg turned).
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdint>
#include <functional>
#include <map>
#include <random>
#include <vector>

#include "../tests/loop/sim_key_frames.h"
#include "frontend/outlier_rejection.h"
#include "loop/bow_database.h"
#include "loop/image_descriptors.h"
#include "loop/loop_closer.h"

namespace {

using namespace vilslam;

constexpr int kRenderedImages = 50;
constexpr double kDeg = M_PI / 180.0;

const test::SimLoopScene& scene() {
  static const test::SimLoopScene s(sim::Scenario::kHighbay, 1);
  return s;
}

// Left-image ORB descriptors at route time fraction f in [0, 1).
cv::Mat left_descriptors(double f, std::uint64_t noise_seed) {
  const test::SimLoopScene& s = scene();
  const TimeNs span_ns = s.motion.end_ns() - s.motion.start_ns();
  const TimeNs t_ns = s.motion.start_ns() + static_cast<TimeNs>(f * static_cast<double>(span_ns));
  const SE3 T_W_C0 = s.motion.pose(t_ns) * s.calib.T_I_C0;
  sim::RenderOptions render;
  render.noise_seed = noise_seed;
  return describe_image(sim::render_image(s.world, s.calib.cam0, [&](TimeNs) { return T_W_C0; }, t_ns, render));
}

// The descriptors of key frame i of a long run: a random 80 % of rendered image i mod 50's (drawn in order of i).
class KeyImageRows {
 public:
  KeyImageRows() : rng_(1), keep_(0.8) {
    for (int i = 0; i < kRenderedImages; ++i) images_.push_back(left_descriptors(static_cast<double>(i) / kRenderedImages, i));
  }
  // Route time fraction of the image key frame i comes from.
  static double fraction(std::size_t i) { return static_cast<double>(i % kRenderedImages) / kRenderedImages; }
  cv::Mat next(std::size_t i) {
    const cv::Mat& d = images_[i % images_.size()];
    cv::Mat kept;
    for (int r = 0; r < d.rows; ++r) {
      if (keep_(rng_)) kept.push_back(d.row(r));
    }
    return kept;
  }

 private:
  std::vector<cv::Mat> images_;
  std::mt19937_64 rng_;
  std::bernoulli_distribution keep_;
};

// N key frames one second apart, built once per N.
const BowDatabase& database(std::size_t n) {
  static std::map<std::size_t, BowDatabase> cache;
  auto it = cache.find(n);
  if (it != cache.end()) return it->second;
  KeyImageRows rows;
  BowDatabase db;
  for (std::size_t i = 0; i < n; ++i) {
    db.add(static_cast<std::int64_t>(i), s_to_ns(static_cast<double>(i)), scene().vocabulary->transform(rows.next(i)));
  }
  return cache.emplace(n, std::move(db)).first->second;
}

void BM_BowQuery(benchmark::State& state) {
  const BowDatabase& db = database(static_cast<std::size_t>(state.range(0)));
  // A new key image between two rendered ones, after every entry and the time gap.
  const BowVector v = scene().vocabulary->transform(left_descriptors(20.5 / kRenderedImages, 1000));
  const loop::LoopClosureConfig config;
  const TimeNs t_ns = s_to_ns(static_cast<double>(db.size()) + config.min_time_gap_s);
  std::vector<LoopCandidate> candidates;
  for (auto _ : state) {
    candidates = db.query(v, t_ns, static_cast<std::size_t>(config.max_bow_candidates), s_to_ns(config.min_time_gap_s));
    benchmark::DoNotOptimize(candidates.data());
  }
  state.counters["entries"] = static_cast<double>(db.size());
  state.counters["query_words"] = static_cast<double>(v.size());
  state.counters["best_score"] = candidates.empty() ? 0.0 : candidates[0].score;
}
BENCHMARK(BM_BowQuery)->Arg(1000)->Arg(5000)->Unit(benchmark::kMillisecond);

// Key frames A (100 s, pose 0) and B (200 s, pose 1) as in test_loop_closer.cpp.
struct Revisit {
  SE3 T_W_IA, T_W_IB;
  loop::KeyFrame A, B;
};

const Revisit& revisit() {
  static const Revisit r = [] {
    const test::SimLoopScene& s = scene();
    const SE3 T_W_IA = s.motion.pose(s.motion.start_ns() + s_to_ns(20.0));
    const SE3 T_W_IB = T_W_IA * SE3(so3::exp(Vec3(0, 0, 15 * kDeg)), Vec3(1.5, 0.4, 0.0));
    return Revisit{T_W_IA, T_W_IB, s.key_frame(T_W_IA, s_to_ns(100.0), 0, 11),
                   s.key_frame(T_W_IB, s_to_ns(200.0), 1, 21)};
  }();
  return r;
}

void BM_LoopConstraint(benchmark::State& state) {
  const Revisit& r = revisit();
  const std::function<SE3(std::size_t)> T_W_L = [&](std::size_t i) {
    return scene().T_W_L(i == 0 ? r.T_W_IA : r.T_W_IB);
  };
  loop::LoopCloser with_A(loop::LoopClosureConfig{}, lidar::LidarConfig{}, scene().vocabulary);
  with_A.add_and_detect(r.A, T_W_L);
  std::vector<loop::LoopCandidateRecord> records;
  for (auto _ : state) {
    state.PauseTiming();
    loop::LoopCloser closer = with_A;  // each iteration verifies B against A from scratch
    loop::KeyFrame B = r.B;
    state.ResumeTiming();
    records = closer.add_and_detect(std::move(B), T_W_L);
    benchmark::DoNotOptimize(records.data());
  }
  if (records.size() != 1 || !records[0].accepted()) {
    state.SkipWithError("the revisit was not accepted");
    return;
  }
  state.counters["descriptor_matches"] = records[0].descriptor_matches;
  state.counters["pnp_inliers"] = records[0].pnp_inliers;
  state.counters["icp_matched"] = records[0].icp_matched_fraction;
}
BENCHMARK(BM_LoopConstraint)->Unit(benchmark::kMillisecond);

// The EPnP step alone, on B's descriptor matches to A's triangulated rows, as LoopCloser::verify calls it.
void BM_LoopEpnp(benchmark::State& state) {
  const Revisit& r = revisit();
  const loop::LoopClosureConfig config;
  std::vector<int> rows;
  cv::Mat train;
  for (int i = 0; i < r.A.image.descriptors.rows; ++i) {
    if (!r.A.image.points_C0[i].allFinite()) continue;
    rows.push_back(i);
    train.push_back(r.A.image.descriptors.row(i));
  }
  std::vector<Vec3> p_C0u;
  std::vector<Eigen::Vector2d> xy_C0v;
  const auto matches = loop::match_descriptors(r.B.image.descriptors, train, config.descriptor_matching);
  for (const loop::DescriptorMatch& m : matches) {
    p_C0u.push_back(r.A.image.points_C0[rows[m.train]]);
    xy_C0v.push_back(r.B.image.left_norm[m.query]);
  }
  FrontendConfig pnp;
  pnp.pnp_min_points = 5;
  pnp.pnp_ransac_iterations = config.pnp_ransac_iterations;
  pnp.pnp_ransac_threshold_px = config.pnp_reprojection_px;
  pnp.ransac_seed = config.pnp_ransac_seed;
  MotionEstimate estimate;
  for (auto _ : state) {
    estimate = estimate_motion_pnp(p_C0u, xy_C0v, r.B.image.focal_px, pnp, PnpSolver::kEPnP);
    benchmark::DoNotOptimize(estimate);
  }
  state.counters["matches"] = static_cast<double>(p_C0u.size());
  state.counters["pnp_inliers"] = estimate.inliers;
}
BENCHMARK(BM_LoopEpnp)->Unit(benchmark::kMillisecond);

// One key frame of a run that re-localizes in a saved map of N key frames: B's query of the map's database and
// the verification of its candidates, with A (the same place) in the map at key frame N / 2 among N - 1 others
// from the long run above (their rows carry no 3D point, so a candidate among them stops at descriptor matching).
// Images of the route within 5 % of A's place are left out of the others, so that A is the place's only key
// frame. Re-localization takes relocalization_loops (2) such key frames.
void BM_MapRelocalization(benchmark::State& state) {
  const Revisit& r = revisit();
  const std::size_t n = static_cast<std::size_t>(state.range(0));
  const test::SimLoopScene& s = scene();
  const double a_fraction = 20.0 / ns_to_s(s.motion.end_ns() - s.motion.start_ns());
  KeyImageRows rows;
  std::vector<loop::KeyFrame> map;
  Trajectory poses;
  for (std::size_t i = 0, source = 0; i < n; ++i) {
    loop::KeyFrame k;
    if (i == n / 2) {
      k = r.A;
    } else {
      while (std::abs(KeyImageRows::fraction(source) - a_fraction) < 0.05) ++source;
      k.image.descriptors = rows.next(source++);
      k.image.left_norm.assign(static_cast<std::size_t>(k.image.descriptors.rows), Eigen::Vector2d::Zero());
      k.image.points_C0.assign(static_cast<std::size_t>(k.image.descriptors.rows), Vec3::Constant(std::nan("")));
      k.image.bow = s.vocabulary->transform(k.image.descriptors);
      k.image.focal_px = r.A.image.focal_px;
    }
    k.pose_index = i;
    k.scan_t_ns = k.image.t_ns = s_to_ns(static_cast<double>(i + 1));
    map.push_back(std::move(k));
    poses.push_back({map.back().scan_t_ns, i == n / 2 ? s.T_W_L(r.T_W_IA) : SE3()});
  }
  // Each iteration adds B again, a second later; the time gap keeps the run's own earlier copies of B from being
  // candidates, so every iteration queries and verifies in the map.
  loop::LoopClosureConfig config;
  config.min_time_gap_s = 1e9;
  loop::LoopCloser closer(config, lidar::LidarConfig{}, s.vocabulary);
  closer.load_map(std::move(map), std::move(poses));
  const std::function<SE3(std::size_t)> T_W_L = [&](std::size_t) { return s.T_W_L(r.T_W_IB); };
  std::vector<loop::LoopCandidateRecord> records;
  TimeNs t_ns = r.B.image.t_ns;
  for (auto _ : state) {
    state.PauseTiming();
    loop::KeyFrame B = r.B;
    B.pose_index = 0;
    B.image.t_ns = B.scan_t_ns = (t_ns += s_to_ns(1.0));
    state.ResumeTiming();
    records = closer.add_and_detect(std::move(B), T_W_L);
    benchmark::DoNotOptimize(records.data());
  }
  if (records.empty() || !records.back().accepted() || !records.back().map_candidate ||
      records.back().candidate_key_frame != n / 2) {
    state.SkipWithError("B did not find A in the map");
    return;
  }
  state.counters["map_key_frames"] = static_cast<double>(n);
  state.counters["candidates_verified"] = static_cast<double>(records.size());
}
BENCHMARK(BM_MapRelocalization)->Arg(1000)->Arg(5000)->Unit(benchmark::kMillisecond);

}  // namespace
