#include <gtest/gtest.h>

#include "lidar/dewarp.h"
#include "synthetic_scene.h"

namespace vilslam::lidar {
namespace {

// Distance from a world point to the nearest surface of the scene (room faces and block faces).
double distance_to_surfaces(const test::Scene& scene, const Vec3& p) {
  double best = std::numeric_limits<double>::infinity();
  for (int k = 0; k < 3; ++k) {
    best = std::min({best, std::abs(p[k] - scene.room.lo[k]), std::abs(p[k] - scene.room.hi[k])});
  }
  for (const test::Box& b : scene.blocks) {
    const Vec3 outside = (b.lo - p).cwiseMax(p - b.hi).cwiseMax(0.0);
    best = std::min(best, outside.norm());
  }
  return best;
}

TEST(Dewarp, MovingScanLandsOnTheSceneFromTheEndPose) {
  const test::Scene scene = test::box_room();
  const LidarScan raw = test::sweep(scene, test::moving_pose, 0);
  const SE3 T_W_end = test::moving_pose(raw.end_t_ns());
  double raw_max = 0.0;
  for (const LidarPoint& p : raw.points) {
    raw_max = std::max(raw_max, distance_to_surfaces(scene, T_W_end * Vec3(p.x, p.y, p.z)));
  }
  EXPECT_GT(raw_max, 0.2);  // without dewarping the sweep is visibly distorted
  const LidarScan dewarped = dewarp(raw, test::moving_pose);
  ASSERT_EQ(dewarped.points.size(), raw.points.size());
  const float end_offset_s = static_cast<float>(ns_to_s(raw.end_t_ns() - raw.t_ns));
  for (const LidarPoint& p : dewarped.points) {
    ASSERT_LT(distance_to_surfaces(scene, T_W_end * Vec3(p.x, p.y, p.z)), 1e-4);
    ASSERT_FLOAT_EQ(p.t_offset_s, end_offset_s);
  }
}

TEST(Dewarp, FeaturePointsMoveToTheEndFrame) {
  const test::Scene scene = test::box_room();
  const LidarScan raw = test::sweep(scene, test::moving_pose, 5 * kNsPerSecond / 100);
  const FeatureScan features = extract_features(raw, RingConfig{}, FeatureConfig{});
  ASSERT_GT(features.surfaces.size(), 100u);
  const TimeNs end_t_ns = raw.end_t_ns();
  const FeatureScan dewarped = dewarp(features, end_t_ns, test::moving_pose);
  const SE3 T_W_end = test::moving_pose(end_t_ns);
  ASSERT_EQ(dewarped.surfaces.size(), features.surfaces.size());
  for (const FeaturePoint& f : dewarped.surfaces) {
    ASSERT_LT(distance_to_surfaces(scene, T_W_end * f.p_L), 1e-6);
  }
  // A normal turns with its point: the surface's normal in the end frame (ring features have none; give them one).
  FeatureScan with_normals = features;
  for (FeaturePoint& f : with_normals.surfaces) f.normal_L = Vec3::UnitZ();
  const FeatureScan turned = dewarp(with_normals, end_t_ns, test::moving_pose);
  for (std::size_t i = 0; i < turned.surfaces.size(); ++i) {
    const SE3 T_W_i = test::moving_pose(raw.t_ns + s_to_ns(features.surfaces[i].t_offset_s));
    EXPECT_LT((T_W_end.rotation() * turned.surfaces[i].normal_L - T_W_i.rotation() * Vec3::UnitZ()).norm(), 1e-9);
  }
  for (std::size_t i = 0; i < features.edges.size(); ++i) {
    // Each edge point is the world point it was, seen from the end pose (paper eq.: P~ = T_{k+1}^-1 T_i P).
    const FeaturePoint& before = features.edges[i];
    const Vec3 p_W = test::moving_pose(raw.t_ns + s_to_ns(before.t_offset_s)) * before.p_L;
    EXPECT_LT((T_W_end * dewarped.edges[i].p_L - p_W).norm(), 1e-9);
  }
}

}  // namespace
}  // namespace vilslam::lidar
