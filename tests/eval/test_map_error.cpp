#include <gtest/gtest.h>

#include <random>

#include "eval/map_error.h"
#include "test_util.h"

namespace vilslam::eval {
namespace {

// Points on three planes of a room corner and a box, so that ICP is well constrained.
PointCloud structured_cloud(std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 10.0f);
  PointCloud cloud;
  for (int i = 0; i < 3000; ++i) {
    cloud.points.emplace_back(u(rng), u(rng), 0.0f);
    cloud.points.emplace_back(u(rng), 0.0f, 0.5f * u(rng));
    cloud.points.emplace_back(0.0f, u(rng), 0.5f * u(rng));
    cloud.points.emplace_back(3.0f + 0.2f * u(rng), 4.0f, 0.2f * u(rng));
    cloud.points.emplace_back(3.0f, 4.0f + 0.2f * u(rng), 0.2f * u(rng));
  }
  return cloud;
}

PointCloud moved(const PointCloud& cloud, const SE3& T) {
  PointCloud out;
  for (const auto& p : cloud.points) out.points.push_back((T * p.cast<double>()).cast<float>());
  return out;
}

const SE3 kOffset(so3::exp_quat(Vec3(0.01, -0.02, 0.05)), Vec3(0.3, -0.2, 0.1));

class MapErrorModes : public ::testing::TestWithParam<IcpMode> {};

TEST_P(MapErrorModes, CloudAgainstItselfAfterKnownOffset) {
  const PointCloud model = structured_cloud(1);
  const PointCloud map = moved(model, kOffset);
  MapErrorConfig config;
  config.icp.mode = GetParam();
  const MapError aligned = compute_map_error(map, model, config);
  EXPECT_TRUE(aligned.icp.converged);
  EXPECT_LT(aligned.mean_m, 1e-4);
  EXPECT_LT(aligned.p95_m, 1e-4);
  const SE3 residual = aligned.icp.T_model_map * kOffset;  // identity when the offset is undone
  EXPECT_LT(residual.translation().norm(), 1e-4);
  EXPECT_LT(so3::log(residual.quat()).norm(), 1e-5);
  ASSERT_EQ(aligned.per_point_m.size(), map.size());

  config.align = false;
  const MapError raw = compute_map_error(map, model, config);
  EXPECT_GT(raw.mean_m, 0.05);
  EXPECT_GT(raw.p95_m, raw.median_m);
  EXPECT_EQ(raw.icp.iterations, 0);
}

// ICP on a strided subsample of the map lands on the same alignment; errors still cover every point.
TEST(MapError, SubsampledIcpKeepsTheAlignmentAndScoresEveryPoint) {
  const PointCloud model = structured_cloud(3);
  const PointCloud map = moved(model, kOffset);
  MapErrorConfig config;
  config.max_icp_points = 1000;  // of 15000
  const MapError e = compute_map_error(map, model, config);
  EXPECT_TRUE(e.icp.converged);
  EXPECT_LE(e.icp.inliers, 1000u);
  const SE3 residual = e.icp.T_model_map * kOffset;
  EXPECT_LT(residual.translation().norm(), 1e-3);
  EXPECT_LT(so3::log(residual.quat()).norm(), 1e-4);
  ASSERT_EQ(e.per_point_m.size(), map.size());
  EXPECT_LT(e.p95_m, 1e-3);
}

INSTANTIATE_TEST_SUITE_P(Icp, MapErrorModes, ::testing::Values(IcpMode::kPointToPoint, IcpMode::kPointToPlane));

TEST(MapError, IsDeterministic) {
  const PointCloud model = structured_cloud(2);
  const PointCloud map = moved(structured_cloud(3), kOffset);
  const MapError a = compute_map_error(map, model, {});
  const MapError b = compute_map_error(map, model, {});
  EXPECT_EQ(a.per_point_m, b.per_point_m);
  EXPECT_EQ(a.icp.T_model_map.matrix(), b.icp.T_model_map.matrix());
}

TEST(MapError, MeasuresAKnownSurfaceOffset) {
  // A map 5 cm above a dense floor: after nothing but NN distances, every error is 5 cm.
  PointCloud model, map;
  for (int x = 0; x <= 200; ++x) {
    for (int y = 0; y <= 200; ++y) model.points.emplace_back(0.01f * x, 0.01f * y, 0.0f);
  }
  for (int k = 0; k < 100; ++k) map.points.emplace_back(0.2f + 0.01f * k, 1.0f, 0.05f);
  MapErrorConfig config;
  config.align = false;
  const MapError e = compute_map_error(map, model, config);
  EXPECT_NEAR(e.mean_m, 0.05, 1e-6);
  EXPECT_NEAR(e.median_m, 0.05, 1e-6);
  EXPECT_NEAR(e.p95_m, 0.05, 1e-6);
}

// A real LiDAR scan against itself after the known offset: ICP undoes it on real structure.
TEST(MapError, RealScanAgainstItselfAfterKnownOffset) {
  VILSLAM_REQUIRE_SHARED_DATA(path, "lidar/small_gicp/target.ply");
  const PointCloud model = read_cloud(path);
  const MapError e = compute_map_error(moved(model, kOffset), model, {});
  const SE3 residual = e.icp.T_model_map * kOffset;
  EXPECT_LT(residual.translation().norm(), 1e-3);
  EXPECT_LT(so3::log(residual.quat()).norm(), 1e-4);
  EXPECT_LT(e.median_m, 1e-3);
  MapErrorConfig raw;
  raw.align = false;
  EXPECT_GT(compute_map_error(moved(model, kOffset), model, raw).median_m, 0.05);
}

}  // namespace
}  // namespace vilslam::eval
