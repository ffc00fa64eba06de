// Mixed pixels on simulated sweeps of the highbay's racks, by a spinning sensor (judged along its rings) and by a
// non-repetitive one (no rings, judged by direction): the simulator puts a return between the near and the far
// surface at depth edges (sim/lidar_returns.h), and mixed_pixels must flag those and leave the returns on
// surfaces alone.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <string>
#include <utility>

#include "lidar/mixed_pixels.h"
#include "sim/lidar_sim.h"
#include "sim/sim_config.h"
#include "sim/trajectory.h"
#include "sim/world.h"

namespace vilslam::lidar {
namespace {

struct Shares {
  double off_surface_flagged = 0;  // of the returns more than 0.15 m from every surface (mixed pixels)
  double on_surface_flagged = 0;   // of the returns within 3 cm of a surface
  std::size_t off_surface = 0;
};

// Sweeps every 2 s along the highbay's route, each point classified by its distance to the world.
Shares flagged_shares(const std::string& sensor, double mixed_pixel_probability) {
  const sim::World world = sim::World::generate(sim::Scenario::kHighbay, 1);
  const sim::RouteMotion motion(world.route_W(), sim::route_motion_config(sim::SimConfig{}, sim::Scenario::kHighbay));
  sim::LidarSimConfig lidar = sim::lidar_sensor(sensor);
  lidar.range_noise_sigma_m = 0.005;
  lidar.returns = sim::ideal_returns();
  lidar.returns.mixed_pixel_probability = mixed_pixel_probability;
  std::size_t off = 0, off_flagged = 0, on = 0, on_flagged = 0;
  for (int k = 0; k < 10; ++k) {
    const TimeNs t0 = s_to_ns(2.0 * k);
    const auto T_W_L = [&motion](TimeNs t) { return motion.pose(t) * SE3(Quat::Identity(), Vec3(0, 0, 0.2)); };
    const LidarScan scan = sim::simulate_sweep(world, lidar, t0, T_W_L, 50 + k);
    const std::vector<bool> mixed = mixed_pixels(scan);
    for (std::size_t i = 0; i < scan.points.size(); ++i) {
      const LidarPoint& p = scan.points[i];
      const TimeNs t = t0 + static_cast<TimeNs>(std::llround(p.t_offset_s * 1e9));
      const double d = world.distance_to_surface(T_W_L(t) * Vec3(p.x, p.y, p.z));
      if (d > 0.15) {
        ++off;
        off_flagged += mixed[i];
      } else if (d < 0.03) {
        ++on;
        on_flagged += mixed[i];
      }
    }
  }
  Shares s;
  s.off_surface = off;
  s.off_surface_flagged = off > 0 ? double(off_flagged) / off : 0.0;
  s.on_surface_flagged = on > 0 ? double(on_flagged) / on : 0.0;
  return s;
}

TEST(MixedPixels, FlagsReturnsBetweenSurfacesAndKeepsThoseOnSurfaces) {
  // Along a ring the neighbours are 0.2 deg apart; without rings the nearest beams are about 1 deg apart, where an
  // oblique surface changes the range as much as a small depth edge, so fewer mixed pixels stand out.
  for (const auto& [sensor, min_share_flagged] : {std::pair<std::string, double>{"vlp16", 0.8}, {"mid360", 0.25}}) {
    const Shares s = flagged_shares(sensor, 1.0);
    ASSERT_GT(s.off_surface, 1000u) << sensor;  // the racks make many depth edges
    EXPECT_GT(s.off_surface_flagged, min_share_flagged) << sensor;
    EXPECT_LT(s.on_surface_flagged, 0.01) << sensor;
  }
}

TEST(MixedPixels, IdealSweepsLoseAlmostNothing) {
  for (const std::string sensor : {"vlp16", "mid360"}) EXPECT_LT(flagged_shares(sensor, 0.0).on_surface_flagged, 0.01);
}

// One ring of a wall at 10 m with a box face at 5 m over azimuths 10-20 deg, 0.2 deg apart.
LidarScan wall_and_box() {
  LidarScan scan;
  for (int k = 0; k < 1800; ++k) {
    const double az = k * 0.2 * M_PI / 180.0;
    const double az_deg = k * 0.2;
    const double r = az_deg >= 10.0 && az_deg < 20.0 ? 5.0 : 10.0;
    LidarPoint p;
    p.x = static_cast<float>(r * std::cos(az));
    p.y = static_cast<float>(r * std::sin(az));
    scan.points.push_back(p);
  }
  return scan;
}

TEST(MixedPixels, FlagsOnlyTheReturnBetweenNeighbours) {
  LidarScan scan = wall_and_box();
  const std::size_t veil = 100;  // 20.0 deg, the first wall return after the box: put it half way
  scan.points[veil].x *= 0.75f;
  scan.points[veil].y *= 0.75f;
  const std::vector<bool> mixed = mixed_pixels(scan);
  for (std::size_t i = 0; i < scan.points.size(); ++i) EXPECT_EQ(mixed[i], i == veil) << "point " << i;
}

TEST(MixedPixels, NoJudgementAcrossAMissedEcho) {
  LidarScan scan = wall_and_box();
  scan.points[100].x *= 0.75f;
  scan.points[100].y *= 0.75f;
  scan.points.erase(scan.points.begin() + 101, scan.points.begin() + 104);  // three missed echoes after it
  EXPECT_FALSE(mixed_pixels(scan)[100]);
}

TEST(MixedPixels, WithoutRingsTheNearestBeamsByDirectionJudge) {
  LidarScan scan = wall_and_box();
  const std::size_t veil = 100;
  scan.points[veil].x *= 0.75f;
  scan.points[veil].y *= 0.75f;
  scan.has_ring = false;
  const std::vector<bool> mixed = mixed_pixels(scan);
  for (std::size_t i = 0; i < scan.points.size(); ++i) EXPECT_EQ(mixed[i], i == veil) << "point " << i;
}

}  // namespace
}  // namespace vilslam::lidar
