#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

#include "eval/icp.h"
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

// The estimator's world W_e is the model's world W_g moved by a large rigid motion (85 deg of yaw, 2 m, as a
// VIO's initial frame can be): ground truth T_Wg_L(t) moves along a curve sampled at 200 Hz, the estimate is
// T_We_L = T_We_Wg T_Wg_L sampled at other instants, and the map is the model seen in W_e.
const SE3 kWeWg(so3::exp_quat(Vec3(0.02, -0.01, 85.0 * M_PI / 180.0)), Vec3(1.5, -2.0, 0.4));

Trajectory ground_truth_curve() {
  Trajectory gt;
  for (int i = 0; i <= 400; ++i) {
    const double t = 0.005 * i;
    gt.push_back({s_to_ns(1.0 + t), SE3(so3::exp_quat(Vec3(0.0, 0.1 * t, 0.8 * t)), Vec3(2.0 + t, 3.0 + 0.5 * t * t, 1.0))});
  }
  return gt;
}

// Estimated poses at 1.0123 s, 1.1123 s, ... (between ground-truth samples), in W_e.
Trajectory estimate_in_other_world(const Trajectory& gt) {
  Trajectory est;
  for (int i = 0; i < 15; ++i) {
    const TimeNs t_ns = s_to_ns(1.0123 + 0.1 * i);
    est.push_back({t_ns, kWeWg * pose_at(gt, t_ns)});
  }
  return est;
}

TEST(MapError, FirstPoseAlignmentRecoversAFarOffsetWhereIdentityIcpFails) {
  const PointCloud model = structured_cloud(4);
  const PointCloud map = moved(model, kWeWg);  // p_We = T_We_Wg p_Wg
  const Trajectory gt = ground_truth_curve();
  const InitialAlignment initial = first_pose_alignment(estimate_in_other_world(gt), gt);
  ASSERT_TRUE(initial.first_pose_t_ns.has_value());
  EXPECT_EQ(*initial.first_pose_t_ns, s_to_ns(1.0123));
  const SE3 exact = initial.T_model_map * kWeWg;  // identity when the rule found T_Wg_We
  EXPECT_LT(exact.translation().norm(), 1e-9);
  EXPECT_LT(so3::log(exact.quat()).norm(), 1e-9);

  MapErrorConfig config;
  config.initial = initial;
  const MapError e = compute_map_error(map, model, config);
  EXPECT_TRUE(e.icp.converged);
  EXPECT_LT(e.mean_m, 1e-4);
  const SE3 residual = e.icp.T_model_map * kWeWg;
  EXPECT_LT(residual.translation().norm(), 1e-4);

  // From the identity, ICP does not converge and stops far from the offset.
  const MapError from_identity = compute_map_error(map, model, MapErrorConfig{});
  EXPECT_FALSE(from_identity.icp.converged);
  EXPECT_GT((from_identity.icp.T_model_map * kWeWg).translation().norm(), 0.5);
  EXPECT_GT(from_identity.mean_m, 0.1);

  // No ICP: the map measured under the first-pose alignment alone.
  config.align = false;
  const MapError first_pose_only = compute_map_error(map, model, config);
  EXPECT_EQ(first_pose_only.icp.iterations, 0);
  EXPECT_EQ(first_pose_only.icp.T_model_map.matrix(), initial.T_model_map.matrix());
  EXPECT_LT(first_pose_only.mean_m, 1e-4);
}

TEST(MapError, FirstPoseAlignmentUsesTheFirstPoseOnly) {
  const Trajectory gt = ground_truth_curve();
  const Trajectory est = estimate_in_other_world(gt);
  Trajectory drifted = est;  // every later pose off by a growing error: the alignment does not change
  for (std::size_t i = 1; i < drifted.size(); ++i)
    drifted[i].T_W_B = SE3(so3::exp_quat(Vec3(0, 0, 0.01 * i)), Vec3(0.1 * i, 0, 0)) * drifted[i].T_W_B;
  EXPECT_EQ(first_pose_alignment(drifted, gt).T_model_map.matrix(), first_pose_alignment(est, gt).T_model_map.matrix());
  // The ground truth is interpolated at t0: without interpolation (the nearest sample) it would be off.
  const SE3 T = first_pose_alignment(est, gt).T_model_map;
  EXPECT_TRUE((T * est.front().T_W_B).translation().isApprox(pose_at(gt, est.front().t_ns).translation(), 1e-12));
  EXPECT_GT(((T * est.front().T_W_B).translation() - gt[2].T_W_B.translation()).norm(), 1e-3);
}

TEST(MapError, FirstPoseAlignmentRejectsAFirstPoseOutsideTheGroundTruth) {
  const Trajectory gt = ground_truth_curve();
  Trajectory early = estimate_in_other_world(gt);
  early.front().t_ns = gt.front().t_ns - 1;
  EXPECT_THROW(first_pose_alignment(early, gt), std::invalid_argument);
  Trajectory late = {{gt.back().t_ns + 1, SE3()}};
  EXPECT_THROW(first_pose_alignment(late, gt), std::invalid_argument);
  EXPECT_THROW(first_pose_alignment({}, gt), std::invalid_argument);
  EXPECT_THROW(first_pose_alignment(estimate_in_other_world(gt), {gt.front()}), std::invalid_argument);
  EXPECT_NO_THROW(first_pose_alignment({{gt.back().t_ns, SE3()}}, gt));  // the span's ends are inside
}

// A part of the map lying 4 cm off the surfaces the rest of the map lies on (a double wall): measured
// under the whole map's alignment it shows the offset; aligned on its own, ICP hides it.
TEST(MapError, PartMeasuredInTheWholeMapsAlignmentShowsADoubleSurface) {
  const PointCloud model = structured_cloud(5);
  const PointCloud whole = moved(model, kOffset);
  PointCloud part;
  const SE3 shift(Quat::Identity(), Vec3(0.04, 0.04, 0.04));  // 4 cm off every plane of the cloud
  for (std::size_t i = 0; i < whole.size(); i += 51)  // 51: points of all five planes (they alternate)
    part.points.push_back((shift * whole.points[i].cast<double>()).cast<float>());
  const MapError in_whole = compute_map_error(part, whole, model, MapErrorConfig{});
  const MapError alone = compute_map_error(part, model, MapErrorConfig{});
  ASSERT_EQ(in_whole.per_point_m.size(), part.size());
  EXPECT_EQ(in_whole.icp.T_model_map.matrix(), compute_map_error(whole, model, MapErrorConfig{}).icp.T_model_map.matrix());
  std::printf("4 cm double surface: MRE in the whole map's alignment %.4f m, aligned alone %.4f m\n", in_whole.mean_m,
              alone.mean_m);
  EXPECT_GT(in_whole.median_m, 0.03);
  EXPECT_LT(alone.median_m, 0.01);
}

// A real LiDAR scan against itself after the known offset: ICP undoes it on real structure.
// A tube along x (a tunnel without ends): no surface constrains x. ICP corrects
// the offset across the tube and keeps the initial alignment along the unconstrained directions instead of
// sliding the map along the tube.
TEST(MapError, IcpKeepsTheInitialAlignmentAlongAnUnconstrainedTunnelAxis) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> along(0.0, 40.0), angle(0.0, 2 * M_PI);
  std::vector<Eigen::Vector3f> tube;
  for (int i = 0; i < 20000; ++i) {
    const double a = angle(rng);
    tube.emplace_back(static_cast<float>(along(rng)), static_cast<float>(3.0 * std::cos(a)), static_cast<float>(3.0 * std::sin(a)));
  }
  const PointIndex model(tube);
  const std::vector<Eigen::Vector3f> normals = estimate_normals(model, 10);
  std::vector<Eigen::Vector3f> map;
  for (std::size_t i = 0; i < tube.size(); i += 7) map.push_back(tube[i]);
  const SE3 initial(Quat::Identity(), Vec3(0.5, 0.06, -0.04));  // 0.5 m along the axis, 7 cm across it
  const IcpResult r = align_icp(map, model, normals, IcpConfig{}, initial);
  EXPECT_GE(r.degenerate_directions, 1);  // the axis (the roll about it is held by the normals' noise)
  EXPECT_NEAR(r.T_model_map.translation().x(), 0.5, 0.02);  // kept: the map does not slide along the tube
  EXPECT_LT(r.T_model_map.translation().tail<2>().norm(), 0.01);  // corrected across it
  // Without the rule (threshold 0) the solve follows numerical noise along the axis.
  IcpConfig unguarded;
  unguarded.min_eigenvalue_per_match = 0;
  EXPECT_EQ(align_icp(map, model, normals, unguarded, initial).degenerate_directions, 0);
}

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
