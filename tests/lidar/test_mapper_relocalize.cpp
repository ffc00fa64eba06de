// Loop correction fed back to LiDAR mapping (paper, "Re-localization"): after relocalize() the mapper
// registers against the map rebuilt from the given scans and continues in the corrected frame.
#include <gtest/gtest.h>

#include "lidar/lidar_mapper.h"
#include "lidar/synthetic_scene.h"

namespace vilslam::lidar {
namespace {

constexpr TimeNs kPeriodNs = 100'000'000;

// The sensor moves 0.25 m along x per sweep; each sweep is taken at a fixed pose (no dewarping needed).
SE3 true_T_W_L(int k) { return SE3(Quat(Eigen::AngleAxisd(0.02 * k, Vec3::UnitZ())), Vec3(0.25 * k, 0.1 * k, 0)); }

LidarScan sweep_at(int k) {
  return test::sweep(test::box_room(), [k](TimeNs) { return true_T_W_L(k); }, k * kPeriodNs, 0.1);
}

// The IMU-rate prior of each sweep: its true pose over the sweep's period (the IMU frame is the LiDAR frame).
SE3 prior(TimeNs t_ns) { return true_T_W_L(static_cast<int>(t_ns / kPeriodNs)); }

double translation_m(const SE3& a, const SE3& b) { return (a.translation() - b.translation()).norm(); }
double rotation_deg(const SE3& a, const SE3& b) { return so3::log((a.inverse() * b).rotation()).norm() * 180 / M_PI; }

TEST(LidarMapperRelocalize, ContinuesInTheCorrectedFrameOnTheRebuiltMap) {
  LidarMapper mapper(LidarMapperConfig{}, SE3());
  std::vector<LidarScan> sweeps;
  for (int k = 0; k < 6; ++k) sweeps.push_back(sweep_at(k));
  mapper.process(sweeps[0], prior);
  const FeatureScan first_features = mapper.last_features();
  for (int k = 1; k < 3; ++k) mapper.process(sweeps[k], prior);
  // A loop correction moves the whole trajectory by G (1 m, 10 degrees of yaw): the mapper resumes from the
  // corrected last pose on a map of the first sweep alone at its corrected pose.
  const SE3 G(Quat(Eigen::AngleAxisd(10 * M_PI / 180, Vec3::UnitZ())), Vec3(1.0, -0.5, 0.2));
  const SE3 corrected_last = G * mapper.process(sweeps[3], prior).T_W_L;
  mapper.relocalize(corrected_last, {{&first_features, G * true_T_W_L(0)}});
  EXPECT_EQ(mapper.map().surfaces.num_points() + mapper.map().edges.num_points() > 0, true);
  for (int k = 4; k < 6; ++k) {
    const LidarMappingResult r = mapper.process(sweeps[k], prior);
    // One sweep's features as the map: registration to about a centimetre.
    EXPECT_LT(translation_m(r.T_W_L, G * true_T_W_L(k)), 0.02) << "sweep " << k;
    EXPECT_LT(rotation_deg(r.T_W_L, G * true_T_W_L(k)), 0.2) << "sweep " << k;
    EXPECT_GT(translation_m(r.T_W_L, true_T_W_L(k)), 0.5) << "sweep " << k << " stayed in the old frame";
  }
}

TEST(LidarMapperRelocalize, MapHoldsOnlyTheGivenScansAtTheirPoses) {
  LidarMapper mapper(LidarMapperConfig{}, SE3());
  mapper.process(sweep_at(0), prior);
  const FeatureScan features = mapper.last_features();
  const SE3 G(Quat::Identity(), Vec3(0, 0, 3.0));
  mapper.relocalize(G, {{&features, G}});
  // Every map point is a feature point of the sweep lifted by 3 m (the map was rebuilt, not extended).
  const FeatureMap alone = build_feature_map(LidarMapperConfig{}.lidar.map, {{&features, G}}, G.translation());
  EXPECT_EQ(mapper.map().surfaces.points(), alone.surfaces.points());
  EXPECT_EQ(mapper.map().edges.points(), alone.edges.points());
  for (const Vec3& p : mapper.map().surfaces.points()) EXPECT_GT(p.z(), 3.0 - 2.0 - 1e-6);  // floor at z = -2
}

TEST(LidarMapperRelocalize, BeforeTheFirstSweepIsAnError) {
  LidarMapper mapper(LidarMapperConfig{}, SE3());
  EXPECT_THROW(mapper.relocalize(SE3(), {}), std::logic_error);
}

}  // namespace
}  // namespace vilslam::lidar
