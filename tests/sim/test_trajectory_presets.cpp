#include <gtest/gtest.h>

#include <iostream>

#include "sim/sim_config.h"
#include "sim/trajectory.h"
#include "sim/world.h"

namespace vilslam::sim {
namespace {

// Every preset route flown with the simulator's motion: about the paper's length, closed, speeds in
// the walking (indoor) or faster (outdoor) range, gentle accelerations.
TEST(RouteMotion, PresetsHaveThePapersLengthsAndSpeeds) {
  const SimConfig config;
  for (Scenario scenario : {Scenario::kHighbay, Scenario::kHallway, Scenario::kTunnel, Scenario::kLoop,
                            Scenario::kOutdoor}) {
    const World world = World::generate(scenario, 1);
    const RouteMotion motion(world.route_W(), route_motion_config(config, scenario));
    const std::string name = scenario_name(scenario);
    EXPECT_NEAR(motion.length_m(), preset_length_m(scenario), 0.1 * preset_length_m(scenario)) << name;
    const bool outdoor = scenario == Scenario::kOutdoor;
    const double lo = outdoor ? 3.0 : 1.0, hi = outdoor ? 5.0 : 1.4;
    EXPECT_GE(motion.cruise_speed_m_s(), lo) << name;
    EXPECT_LE(motion.cruise_speed_m_s(), hi) << name;
    double max_speed = 0, max_accel = 0, min_clearance = 1e9;
    for (TimeNs t = motion.start_ns(); t <= motion.end_ns(); t += 50'000'000) {
      const MotionState s = motion.state(t);
      max_speed = std::max(max_speed, s.v_W.norm());
      max_accel = std::max(max_accel, s.a_W.norm());
      min_clearance = std::min(min_clearance, world.distance_to_surface(s.T_W_I.translation()));
    }
    std::cout << name << ": " << motion.length_m() << " m, " << ns_to_s(motion.end_ns() - motion.start_ns())
              << " s, peak acceleration " << max_accel << " m/s^2, clearance " << min_clearance << " m\n";
    EXPECT_LE(max_speed, hi + 1e-6) << name;
    EXPECT_LT(max_accel, outdoor ? 4.0 : 3.0) << name;
    EXPECT_GT(min_clearance, 0.3) << name << ": the rounded route keeps clear of the geometry";
    EXPECT_LT((motion.pose(motion.start_ns()).translation() - motion.pose(motion.end_ns()).translation()).norm(), 1e-6);
  }
}

}  // namespace
}  // namespace vilslam::sim
