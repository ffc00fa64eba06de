#include <gtest/gtest.h>

#include <tbb/global_control.h>

#include <cmath>

#include "sim/lidar_beams.h"
#include "sim/lidar_sim.h"
#include "sim/world.h"

namespace vilslam::sim {
namespace {

// Fast analytic motion: 3 m/s forward, 1 m/s sideways, 90 deg/s yaw and a slow roll, from a route pose.
std::function<SE3(TimeNs)> fast_motion(const Vec3& start_W) {
  return [start_W](TimeNs t_ns) {
    const double t = ns_to_s(t_ns);
    const Quat q = Quat(Eigen::AngleAxisd(M_PI / 2 * t, Vec3::UnitZ())) * Quat(Eigen::AngleAxisd(0.3 * t, Vec3::UnitX()));
    return SE3(q, start_W + Vec3(3.0 * t, 1.0 * t, 0.0));
  };
}

TEST(LidarSim, PointsLieOnSurfacesAtTheirOwnInstantButNotAtTheScanEnd) {
  const World world = World::generate(Scenario::kHighbay, 1);
  const LidarSimConfig config;
  const auto T_W_L = fast_motion(world.route_W()[20]);
  const double three_sigma = 3 * config.range_noise_sigma_m;
  const TimeNs period_ns = s_to_ns(1.0 / config.rate_hz);
  // Three consecutive sweeps of the moving sequence.
  for (int sweep = 0; sweep < 3; ++sweep) {
    const TimeNs t0 = sweep * period_ns;
    const LidarScan scan = simulate_sweep(world, config, t0, T_W_L, 42 + sweep);
    ASSERT_GT(scan.points.size(), 20000u);
    int own_within = 0, end_outside = 0;
    for (const LidarPoint& p : scan.points) {
      const Vec3 p_L(p.x, p.y, p.z);
      const double d_own = world.distance_to_surface(T_W_L(t0 + s_to_ns(p.t_offset_s)) * p_L);
      own_within += d_own <= three_sigma;
      EXPECT_LE(d_own, 6 * config.range_noise_sigma_m);
      end_outside += world.distance_to_surface(T_W_L(t0 + period_ns) * p_L) > three_sigma;
    }
    const double n = static_cast<double>(scan.points.size());
    EXPECT_GT(own_within / n, 0.995) << "sweep " << sweep;
    EXPECT_GT(end_outside / n, 0.5) << "sweep " << sweep << ": the scan-end pose should misplace most points";
  }
}

TEST(LidarSim, NoiseIsGaussianWithTheConfiguredSigmaAndDeterministic) {
  const World world = World::generate(Scenario::kRoom, 1);
  LidarSimConfig config;
  config.range_noise_sigma_m = 0.03;
  const SE3 pose(Quat::Identity(), Vec3(0, 0.5, 1.3));
  const auto still = [&](TimeNs) { return pose; };
  const LidarScan a = simulate_sweep(world, config, 0, still, 7);
  double sum = 0, sum2 = 0;
  for (const LidarPoint& p : a.points) {
    const Vec3 p_L(p.x, p.y, p.z);
    const auto hit = world.raycast(pose.translation(), pose.quat() * p_L.normalized(), 100);
    ASSERT_TRUE(hit);
    const double e = p_L.norm() - hit->range_m;
    sum += e, sum2 += e * e;
  }
  const double n = static_cast<double>(a.points.size());
  EXPECT_NEAR(sum / n, 0.0, 0.002);
  EXPECT_NEAR(std::sqrt(sum2 / n), 0.03, 0.002);
  // Same seed: bit-identical, also with a single thread; another seed: different noise.
  LidarScan b;
  {
    tbb::global_control one_thread(tbb::global_control::max_allowed_parallelism, 1);
    b = simulate_sweep(world, config, 0, still, 7);
  }
  ASSERT_EQ(a.points.size(), b.points.size());
  for (std::size_t i = 0; i < a.points.size(); ++i) {
    ASSERT_EQ(a.points[i].x, b.points[i].x);
    ASSERT_EQ(a.points[i].intensity, b.points[i].intensity);
  }
  const LidarScan c = simulate_sweep(world, config, 0, still, 8);
  ASSERT_EQ(a.points.size(), c.points.size());
  EXPECT_NE(a.points[100].x, c.points[100].x);
}

TEST(LidarSim, RingsTimesAndIntensitiesFollowTheFiringPattern) {
  const World world = World::generate(Scenario::kHallway, 1);
  const LidarSimConfig config;
  const SE3 pose(Quat::Identity(), world.route_W()[5]);
  const LidarScan scan = simulate_sweep(world, config, 1'000'000'000, [&](TimeNs) { return pose; }, 1);
  EXPECT_EQ(scan.t_ns, 1'000'000'000);
  ASSERT_GT(scan.points.size(), 0.9 * 16 * 1800);  // a closed corridor returns almost every beam
  float last_t = -1;
  for (const LidarPoint& p : scan.points) {
    const double elevation = std::atan2(p.z, std::hypot(p.x, p.y));
    EXPECT_NEAR(elevation, ring_elevation_rad(config, p.ring), 0.002);
    EXPECT_GE(p.t_offset_s, last_t);
    EXPECT_LT(p.t_offset_s, 0.1f);
    // The firing time follows the azimuth (counter-clockwise from +x).
    double azimuth = std::atan2(p.y, p.x);
    if (azimuth < 0) azimuth += 2 * M_PI;
    EXPECT_NEAR(p.t_offset_s, azimuth / (2 * M_PI) * 0.1, 1e-3);
    EXPECT_GE(p.intensity, 0.0f);
    EXPECT_LE(p.intensity, 255.0f);
    last_t = p.t_offset_s;
  }
  // Floor returns at grazing incidence are dimmer than wall returns seen head on.
  double floor_i = 0, wall_i = 0;
  int floor_n = 0, wall_n = 0;
  for (const LidarPoint& p : scan.points) {
    if (p.ring == 0 && std::hypot(p.x, p.y) > 4.0) floor_i += p.intensity, ++floor_n;
    if (p.ring == 7 && std::hypot(p.x, p.y) < 1.5) wall_i += p.intensity, ++wall_n;
  }
  ASSERT_GT(floor_n, 0);
  ASSERT_GT(wall_n, 0);
  EXPECT_LT(floor_i / floor_n, wall_i / wall_n);
}

TEST(LidarSim, RejectsABadConfiguration) {
  const World world = World::generate(Scenario::kRoom, 1);
  LidarSimConfig config;
  config.azimuth_step_deg = 0;
  EXPECT_THROW(simulate_sweep(world, config, 0, [](TimeNs) { return SE3(); }, 0), std::invalid_argument);
}

}  // namespace
}  // namespace vilslam::sim
