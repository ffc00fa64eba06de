// build_dense_map on a simulated highbay: with true poses the map lies on the world's surfaces within
// the range noise; drifted poses and skipping the dewarping both make it clearly worse.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "common/error.h"
#include "eval/map_error.h"
#include "map/map_builder.h"
#include "sim/world.h"
#include "simulated_highbay.h"

namespace vilslam::map {
namespace {

// Median exact distance of the map points (every 7th) to the simulated world's surfaces.
double median_distance_to_world(const DenseMap& map, const sim::World& world) {
  const std::vector<Eigen::Vector3f> points = map.points();
  std::vector<double> d;
  for (std::size_t i = 0; i < points.size(); i += 7) d.push_back(world.distance_to_surface(points[i].cast<double>()));
  return test::median(d);
}

// The drift grows linearly from zero at the first pose to xi at the last: T' = Exp(a xi) T.
Trajectory drifted(const Trajectory& T_W_L, const Vec6& xi) {
  Trajectory out = T_W_L;
  const double span = static_cast<double>(T_W_L.back().t_ns - T_W_L.front().t_ns);
  for (TimedPose& p : out) {
    const double a = static_cast<double>(p.t_ns - T_W_L.front().t_ns) / span;
    p.T_W_B = SE3::exp(a * xi) * p.T_W_B;
  }
  return out;
}

// MRE as `vilslam eval-map` computes it (ICP-aligned, against the dataset's reference model).
eval::MapError eval_map(const DenseMap& map, const std::string& dataset) {
  PointCloud cloud;
  cloud.points = map.points();
  const PointCloud model = read_cloud(open_dataset(dataset)->reference_model_path());
  return eval::compute_map_error(cloud, model, eval::MapErrorConfig{});
}

class MapBuilderHighbay : public ::testing::Test {
 protected:
  void SetUp() override {
    dataset_ = test::highbay_preview();
    ASSERT_FALSE(dataset_.empty());
    T_W_L_ = test::groundtruth_lidar_poses(dataset_);
    ASSERT_GT(T_W_L_.size(), 10u);
  }
  std::string dataset_;
  Trajectory T_W_L_;
};

TEST_F(MapBuilderHighbay, TruePosesPutPointsOnSurfacesAndDriftDoesNot) {
  const sim::World world = sim::World::generate(sim::Scenario::kHighbay, test::kHighbaySeed);
  const MapBuildResult truth = build_dense_map(dataset_, T_W_L_, MapBuilderConfig{});
  const std::size_t scans = open_dataset(dataset_)->summary().lidar_scans;
  EXPECT_EQ(truth.stats.sweeps_used + truth.stats.sweeps_skipped, scans);
  EXPECT_GE(truth.stats.sweeps_used, scans - 1);
  EXPECT_GT(truth.map.num_voxels(), 10000u);
  EXPECT_LE(truth.map.num_voxels(), truth.stats.points_inserted);

  Vec6 xi;
  xi << 0.05, 0, 0, 0, 0, 1.0 * M_PI / 180.0;  // 5 cm along x, 1 deg of yaw by the end
  const MapBuildResult drift = build_dense_map(dataset_, drifted(T_W_L_, xi), MapBuilderConfig{});

  const double true_m = median_distance_to_world(truth.map, world);
  const double drift_m = median_distance_to_world(drift.map, world);
  const eval::MapError true_mre = eval_map(truth.map, dataset_);
  const eval::MapError drift_mre = eval_map(drift.map, dataset_);
  std::printf("median distance to the world: true poses %.5f m, drifted %.5f m\n", true_m, drift_m);
  std::printf("eval-map MRE (model spacing 0.2 m) mean/median/p95: true %.4f/%.4f/%.4f m, drifted %.4f/%.4f/%.4f m\n",
              true_mre.mean_m, true_mre.median_m, true_mre.p95_m, drift_mre.mean_m, drift_mre.median_m, drift_mre.p95_m);
  EXPECT_LT(true_m, 0.02);  // the simulated range noise sigma is 0.02 m
  EXPECT_GT(drift_m, 1.5 * true_m);
  EXPECT_GT(drift_mre.median_m, true_mre.median_m);
}

TEST_F(MapBuilderHighbay, DewarpingMattersWhileMoving) {
  const sim::World world = sim::World::generate(sim::Scenario::kHighbay, test::kHighbaySeed);
  MapBuilderConfig config;
  const double dewarped_m = median_distance_to_world(build_dense_map(dataset_, T_W_L_, config).map, world);
  config.dewarp = false;
  const double raw_m = median_distance_to_world(build_dense_map(dataset_, T_W_L_, config).map, world);
  std::printf("median distance to the world: dewarped %.5f m, not dewarped %.5f m\n", dewarped_m, raw_m);
  EXPECT_GT(raw_m, 1.3 * dewarped_m);
}

// Only the poses nearest each sweep end, as `vilslam run` writes lidar.tum.
Trajectory sweep_end_poses(const std::string& dataset, const Trajectory& T_W_L) {
  const auto reader = open_dataset(dataset);
  Trajectory ends;
  while (const auto event = reader->next()) {
    if (const auto* scan = std::get_if<LidarScan>(&event->data)) {
      const TimeNs end = scan->end_t_ns() + reader->calibration().lidar_time_offset_ns;
      const auto it = std::min_element(T_W_L.begin(), T_W_L.end(), [end](const TimedPose& a, const TimedPose& b) {
        return std::llabs(a.t_ns - end) < std::llabs(b.t_ns - end);
      });
      ends.push_back({end, it->T_W_B});
    }
  }
  return ends;
}

TEST_F(MapBuilderHighbay, SweepEndPosesAloneAreInterpolated) {
  const Trajectory ends = sweep_end_poses(dataset_, T_W_L_);
  ASSERT_GT(ends.size(), 3u);
  const MapBuildResult r = build_dense_map(dataset_, ends, MapBuilderConfig{});
  EXPECT_EQ(r.stats.sweeps_skipped, 1u);  // the first sweep starts before the first pose
  EXPECT_EQ(r.stats.sweeps_used, ends.size() - 1);
  const sim::World world = sim::World::generate(sim::Scenario::kHighbay, test::kHighbaySeed);
  EXPECT_LT(median_distance_to_world(r.map, world), 0.025);
}

// Poses that jump by a correction D between two sweep ends (as lidar_global.tum after a loop): dewarping
// with them smears the sweep after the jump over it; with a continuous trajectory for the motion within the
// sweep (--motion lidar.tum) that sweep lies on the surfaces, moved by D.
TEST_F(MapBuilderHighbay, MotionTrajectoryKeepsAJumpOutOfTheSweep) {
  const Trajectory ends = sweep_end_poses(dataset_, T_W_L_);
  ASSERT_GT(ends.size(), 8u);
  const std::size_t k = 5;  // the jump lies between the ends of sweeps k - 1 and k
  const SE3 D(so3::exp(Vec3(0, 0, 2.0 * M_PI / 180.0)), Vec3(0.5, -0.3, 0.05));
  Trajectory jumped = ends;
  for (std::size_t i = k; i < jumped.size(); ++i) jumped[i].T_W_B = D * jumped[i].T_W_B;
  MapBuilderConfig config;
  config.window_start_ns = ends[k].t_ns;
  config.window_end_ns = ends[k].t_ns + 1;  // sweep k only
  const sim::World world = sim::World::generate(sim::Scenario::kHighbay, test::kHighbaySeed);
  const auto distance_after_undoing_D = [&](const MapBuilderConfig& c) {
    DenseMap undone(c.voxel_size_m);
    std::vector<Eigen::Vector3f> points = build_dense_map(dataset_, jumped, c).map.points();
    for (Eigen::Vector3f& p : points) p = (D.inverse() * p.cast<double>()).cast<float>();
    undone.insert(points);
    return median_distance_to_world(undone, world);
  };
  const double smeared_m = distance_after_undoing_D(config);
  config.motion = ends;
  const double kept_m = distance_after_undoing_D(config);
  std::printf("sweep after a 0.58 m / 2 deg jump, median distance to the world: dewarped with the poses %.4f m, "
              "with the motion trajectory %.4f m\n", smeared_m, kept_m);
  EXPECT_LT(kept_m, 0.025);
  EXPECT_GT(smeared_m, 0.05);
}

// Start and end of every sweep in the IMU clock.
std::vector<std::pair<TimeNs, TimeNs>> sweep_spans(const std::string& dataset) {
  const auto reader = open_dataset(dataset);
  std::vector<std::pair<TimeNs, TimeNs>> spans;
  while (const auto event = reader->next()) {
    if (const auto* scan = std::get_if<LidarScan>(&event->data)) {
      const TimeNs offset_ns = reader->calibration().lidar_time_offset_ns;
      spans.push_back({scan->t_ns + offset_ns, scan->end_t_ns() + offset_ns});
    }
  }
  return spans;
}

// The window [end of sweep k, end of sweep k + 3) holds the ends of sweeps k to k + 2: the map is the one
// of poses that cover exactly those sweeps (from the last pose at or before the start of sweep k to the
// first pose at or after the end of sweep k + 2), point for point; complementary windows split the sweeps.
TEST_F(MapBuilderHighbay, WindowSelectsExactlyTheSweepsEndingInIt) {
  const auto spans = sweep_spans(dataset_);
  ASSERT_GT(spans.size(), 8u);
  const std::size_t k = 4;
  MapBuilderConfig window;
  window.window_start_ns = spans[k].second;
  window.window_end_ns = spans[k + 3].second;
  const MapBuildResult in_window = build_dense_map(dataset_, T_W_L_, window);
  EXPECT_EQ(in_window.stats.sweeps_used, 3u);
  EXPECT_EQ(in_window.stats.sweeps_outside_window + in_window.stats.sweeps_used + in_window.stats.sweeps_skipped,
            spans.size());

  const auto first = std::find_if(T_W_L_.rbegin(), T_W_L_.rend(),
                                  [&](const TimedPose& p) { return p.t_ns <= spans[k].first; });
  const auto last = std::find_if(T_W_L_.begin(), T_W_L_.end(),
                                 [&](const TimedPose& p) { return p.t_ns >= spans[k + 2].second; });
  ASSERT_TRUE(first != T_W_L_.rend() && last != T_W_L_.end());
  const Trajectory covering(first.base() - 1, last + 1);
  const MapBuildResult by_poses = build_dense_map(dataset_, covering, MapBuilderConfig{});
  EXPECT_EQ(by_poses.stats.sweeps_used, 3u);
  EXPECT_EQ(in_window.stats.points_inserted, by_poses.stats.points_inserted);
  EXPECT_EQ(in_window.map.points(), by_poses.map.points());

  MapBuilderConfig before, after;
  before.window_end_ns = after.window_start_ns = spans[k].second;
  const MapBuildResult all = build_dense_map(dataset_, T_W_L_, MapBuilderConfig{});
  const MapBuildResult a = build_dense_map(dataset_, T_W_L_, before);
  const MapBuildResult b = build_dense_map(dataset_, T_W_L_, after);
  const std::size_t covered_before = std::count_if(spans.begin(), spans.begin() + k, [&](const auto& span) {
    return span.first >= T_W_L_.front().t_ns && span.second <= T_W_L_.back().t_ns;  // the poses have no gaps
  });
  EXPECT_EQ(a.stats.sweeps_used, covered_before);  // sweeps 0 to k - 1; sweep k ends at the window's end
  EXPECT_EQ(a.stats.sweeps_skipped, all.stats.sweeps_skipped);
  EXPECT_EQ(a.stats.sweeps_used + b.stats.sweeps_used, all.stats.sweeps_used);
  EXPECT_EQ(a.stats.points_inserted + b.stats.points_inserted, all.stats.points_inserted);

  MapBuilderConfig empty;
  empty.window_start_ns = empty.window_end_ns = spans[k].second;
  EXPECT_THROW(build_dense_map(dataset_, T_W_L_, empty), std::invalid_argument);
  MapBuilderConfig beyond;
  beyond.window_start_ns = spans.back().second + 1;
  EXPECT_THROW(build_dense_map(dataset_, T_W_L_, beyond), InputError);
}

TEST_F(MapBuilderHighbay, RangeFilterAndBadInput) {
  MapBuilderConfig near;
  near.max_range_m = 5.0;
  const MapBuildResult r = build_dense_map(dataset_, T_W_L_, near);
  EXPECT_GT(r.stats.points_out_of_range, 0u);
  const MapBuildResult all = build_dense_map(dataset_, T_W_L_, MapBuilderConfig{});
  EXPECT_LT(r.stats.points_inserted, all.stats.points_inserted);

  Trajectory late = T_W_L_;
  for (TimedPose& p : late) p.t_ns += 1000 * kNsPerSecond;
  EXPECT_THROW(build_dense_map(dataset_, late, MapBuilderConfig{}), InputError);
  EXPECT_THROW(build_dense_map(dataset_ + "_missing", T_W_L_, MapBuilderConfig{}), InputError);
  Trajectory repeated = T_W_L_;
  repeated[5].t_ns = repeated[4].t_ns;
  EXPECT_THROW(build_dense_map(dataset_, repeated, MapBuilderConfig{}), std::invalid_argument);
  MapBuilderConfig bad;
  bad.voxel_size_m = std::nan("");
  EXPECT_THROW(build_dense_map(dataset_, T_W_L_, bad), std::invalid_argument);
  MapBuilderConfig bad_mixed;
  bad_mixed.mixed_pixels.min_gap_ratio = 0.0;
  EXPECT_THROW(build_dense_map(dataset_, T_W_L_, bad_mixed), std::invalid_argument);
}

// Every return is either inserted or dropped as a mixed pixel (lidar/mixed_pixels.h); keeping them inserts all.
TEST_F(MapBuilderHighbay, MixedPixelsAreCountedAndLeftOut) {
  const MapBuildResult dropped = build_dense_map(dataset_, T_W_L_, MapBuilderConfig{});
  MapBuilderConfig keep;
  keep.drop_mixed_pixels = false;
  const MapBuildResult kept = build_dense_map(dataset_, T_W_L_, keep);
  EXPECT_GT(dropped.stats.points_mixed, 0u);  // ideal sensors: returns grazing a surface only
  EXPECT_LT(dropped.stats.points_mixed, kept.stats.points_inserted / 50);
  EXPECT_EQ(kept.stats.points_mixed, 0u);
  EXPECT_EQ(dropped.stats.points_inserted + dropped.stats.points_mixed, kept.stats.points_inserted);
}

}  // namespace
}  // namespace vilslam::map
