#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <map>
#include <sstream>

#include "sim/route.h"
#include "sim/world.h"
#include "test_util.h"

namespace vilslam::sim {
namespace {

const Scenario kAll[] = {Scenario::kHighbay, Scenario::kHallway, Scenario::kTunnel,
                         Scenario::kLoop,    Scenario::kOutdoor, Scenario::kRoom};

class WorldTest : public ::testing::TestWithParam<Scenario> {};

TEST_P(WorldTest, RouteIsClosedClearAndOfThePresetLength) {
  const World world = World::generate(GetParam(), 7);
  const auto& route = world.route_W();
  ASSERT_GT(route.size(), 10u);
  EXPECT_EQ(route.front(), route.back());
  const double length = polyline_length(route);
  EXPECT_NEAR(length, preset_length_m(GetParam()), 0.05 * preset_length_m(GetParam()));
  double clearance = 1e9, max_step = 0, max_turn = 0;
  for (std::size_t i = 1; i < route.size(); ++i) {
    clearance = std::min({clearance, world.distance_to_surface(route[i]),
                          world.distance_to_surface(0.5 * (route[i] + route[i - 1]))});
    max_step = std::max(max_step, (route[i] - route[i - 1]).norm());
    const std::size_t next = i + 1 < route.size() ? i + 1 : 1;
    const Vec3 d0 = (route[i] - route[i - 1]).normalized(), d1 = (route[next] - route[i]).normalized();
    max_turn = std::max(max_turn, std::acos(std::clamp(d0.dot(d1), -1.0, 1.0)));
  }
  EXPECT_GE(clearance, 0.5) << scenario_name(GetParam());
  EXPECT_LE(max_step, 0.6);
  EXPECT_LT(max_turn, 0.5) << "turns too sharp for a smooth spline";
  // Every waypoint is inside the world (a ray straight down meets the floor or ground).
  for (std::size_t i = 0; i < route.size(); i += 10) {
    EXPECT_TRUE(world.raycast(route[i], -Vec3::UnitZ(), 5.0).has_value()) << i;
  }
  std::printf("%s: length %.1f m, clearance %.2f m, %zu waypoints\n", scenario_name(GetParam()).c_str(), length,
              clearance, route.size());
}

TEST_P(WorldTest, TargetLengthOverridesThePreset) {
  const double target = GetParam() == Scenario::kRoom ? 10.0 : 200.0;
  const World world = World::generate(GetParam(), 3, target);
  EXPECT_NEAR(polyline_length(world.route_W()), target, 0.05 * target);
}

TEST_P(WorldTest, ShortestAllowedRouteIsStillClosedAndClear) {
  const std::map<Scenario, double> shortest = {{Scenario::kHighbay, 40},  {Scenario::kHallway, 20},
                                               {Scenario::kTunnel, 20},   {Scenario::kLoop, 160},
                                               {Scenario::kOutdoor, 100}, {Scenario::kRoom, 8}};
  const double length = shortest.at(GetParam());
  EXPECT_THROW(World::generate(GetParam(), 1, 0.9 * length), std::invalid_argument);
  EXPECT_THROW(World::generate(GetParam(), 1, -1.0), std::invalid_argument);
  for (const std::uint64_t seed : {1, 2, 3}) {
    const World world = World::generate(GetParam(), seed, length);
    const auto& route = world.route_W();
    EXPECT_NEAR(polyline_length(route), length, 0.05 * length);
    for (std::size_t i = 1; i < route.size(); ++i) {
      ASSERT_GE(world.distance_to_surface(0.5 * (route[i] + route[i - 1])), 0.5) << "seed " << seed << " at " << i;
    }
  }
}

TEST_P(WorldTest, GenerationIsDeterministicPerSeed) {
  const World a = World::generate(GetParam(), 11), b = World::generate(GetParam(), 11);
  const World c = World::generate(GetParam(), 12);
  ASSERT_EQ(a.route_W().size(), b.route_W().size());
  for (std::size_t i = 0; i < a.route_W().size(); ++i) EXPECT_EQ(a.route_W()[i], b.route_W()[i]);
  ASSERT_EQ(a.materials().size(), b.materials().size());
  for (std::size_t i = 0; i < a.materials().size(); ++i) EXPECT_EQ(a.materials()[i].seed, b.materials()[i].seed);
  // The same rays see the same hits in a and b; a different seed changes some of them.
  const Vec3 o = a.route_W()[a.route_W().size() / 3];
  int differ = 0;
  for (int k = 0; k < 360; ++k) {
    const Vec3 d(std::cos(k * M_PI / 180), std::sin(k * M_PI / 180), 0.2 * std::sin(k * 0.1));
    const auto ha = a.raycast(o, d.normalized(), 80), hb = b.raycast(o, d.normalized(), 80);
    const auto hc = c.raycast(o, d.normalized(), 80);
    ASSERT_EQ(ha.has_value(), hb.has_value());
    if (ha) {
      EXPECT_EQ(ha->range_m, hb->range_m);
      EXPECT_EQ(ha->material, hb->material);
      EXPECT_EQ(ha->uv_m, hb->uv_m);
    }
    if (ha.has_value() != hc.has_value() || (ha && (ha->range_m != hc->range_m || ha->uv_m != hc->uv_m))) ++differ;
  }
  EXPECT_GT(differ, 0);
}

INSTANTIATE_TEST_SUITE_P(Scenarios, WorldTest, ::testing::ValuesIn(kAll),
                         [](const auto& info) { return scenario_name(info.param); });

TEST(Route, StartMidLongestEdgeKeepsTheLoopAndStartsOnAStraight) {
  const Polygon2 corners = {{0, 0}, {4, 0}, {4, 1}, {0, 1}};
  const Polygon2 moved = start_mid_longest_edge(corners);
  ASSERT_EQ(moved.size(), 5u);
  EXPECT_EQ(moved[0], Eigen::Vector2d(2, 0));
  EXPECT_EQ(moved[1], Eigen::Vector2d(4, 0));
  EXPECT_EQ(moved[4], Eigen::Vector2d(0, 0));
  EXPECT_NEAR(rounded_loop_length(moved, 0.3), rounded_loop_length(corners, 0.3), 1e-12);
  const std::vector<Vec3> route = rounded_loop(moved, 0.3, 0.1, 1.0);
  EXPECT_NEAR(polyline_length(route), rounded_loop_length(corners, 0.3), 0.01);
  // Start and end on the straight: the route leaves and arrives along +x.
  EXPECT_NEAR(route.front().y(), 0.0, 1e-12);
  EXPECT_NEAR((route[1] - route[0]).normalized().x(), 1.0, 1e-9);
  EXPECT_NEAR((route.back() - route[route.size() - 2]).normalized().x(), 1.0, 1e-9);
}

TEST(World, HallwayRouteStartsMidCorridorHeadingAlongIt) {
  const World world = World::generate(Scenario::kHallway, 1);
  const auto& route = world.route_W();
  // The start is on a straight: the legs before and after it point the same way.
  const Vec3 in = (route.back() - route[route.size() - 2]).normalized(), out = (route[1] - route[0]).normalized();
  EXPECT_GT(in.dot(out), 0.9999);
  // At least 5 m of straight corridor ahead and behind.
  for (std::size_t k = 1; k <= 10; ++k) {
    EXPECT_GT((route[k + 1] - route[k]).normalized().dot(out), 0.9999) << k;
    EXPECT_GT((route[route.size() - k] - route[route.size() - k - 1]).normalized().dot(out), 0.9999) << k;
  }
}

TEST(World, ParseScenarioRoundTripsAndRejectsUnknownNames) {
  for (const Scenario s : kAll) EXPECT_EQ(parse_scenario(scenario_name(s)), s);
  EXPECT_THROW(parse_scenario("cave"), std::invalid_argument);
}

// Every 20th position of a TUM ground-truth file.
std::vector<Vec3> flight_positions(const std::string& path) {
  std::ifstream in(path);
  std::vector<Vec3> positions;
  std::string line;
  for (int n = 0; std::getline(in, line);) {
    if (line.empty() || line[0] == '#' || n++ % 20) continue;
    std::istringstream ss(line);
    double t;
    Vec3 p;
    ss >> t >> p.x() >> p.y() >> p.z();
    positions.push_back(p);
  }
  return positions;
}

// The flight stays inside the world, clear of its surfaces.
void expect_flight_inside(const World& world, const std::vector<Vec3>& flight, const std::string& name) {
  EXPECT_GT(flight.size(), 50u) << name;
  double clearance = 1e9;
  for (const Vec3& p : flight) {
    EXPECT_TRUE(world.bounds().contains(p)) << name << " " << p.transpose();
    clearance = std::min(clearance, world.distance_to_surface(p));
  }
  EXPECT_GT(clearance, 0.3) << name;
}

TEST(World, RoomContainsTheEurocV1Trajectories) {
  VILSLAM_REQUIRE_SHARED_DATA(dir, "euroc/groundtruth");
  const World world = World::generate(Scenario::kRoom, 1);
  for (const char* name : {"V1_01_easy.txt", "V1_02_medium.txt", "V1_03_difficult.txt"}) {
    const std::vector<Vec3> flight = flight_positions(dir + "/" + name);
    expect_flight_inside(world, flight, name);
    // A flight the Vicon room holds gets that room, not a grown one.
    Eigen::AlignedBox3d box;
    for (const Vec3& p : flight) box.extend(p);
    EXPECT_TRUE(World::generate(Scenario::kRoom, 1, 0, box).bounds().isApprox(world.bounds())) << name;
  }
}

TEST(World, RoomGrowsAroundMachineHallFlightsAndEveryViewHitsAWall) {
  VILSLAM_REQUIRE_SHARED_DATA(dir, "euroc/groundtruth");
  for (const char* name : {"MH_01_easy.txt", "MH_03_medium.txt", "MH_05_difficult.txt"}) {
    const std::vector<Vec3> flight = flight_positions(dir + "/" + name);
    Eigen::AlignedBox3d box;
    for (const Vec3& p : flight) box.extend(p);
    ASSERT_FALSE(World::generate(Scenario::kRoom, 1).bounds().contains(box)) << name << ": fits the Vicon room";
    const World world = World::generate(Scenario::kRoom, 1, 0, box);
    expect_flight_inside(world, flight, name);
    // No blank views: rays in 26 directions from every 10th sampled position hit a surface within 30 m.
    for (std::size_t i = 0; i < flight.size(); i += 10) {
      for (int dx = -1; dx <= 1; ++dx)
        for (int dy = -1; dy <= 1; ++dy)
          for (int dz = -1; dz <= 1; ++dz) {
            if (dx == 0 && dy == 0 && dz == 0) continue;
            const Vec3 dir_W = Vec3(dx, dy, dz).normalized();
            EXPECT_TRUE(world.raycast(flight[i], dir_W, 30.0)) << name << " from " << flight[i].transpose();
          }
    }
  }
}

TEST(World, SurfaceSamplesLieOnSurfacesAndHiddenFacesAreLeftOut) {
  const World world = World::generate(Scenario::kHighbay, 5);
  const PointCloud cloud = world.sample_surfaces(0.2);
  ASSERT_GT(cloud.size(), 10000u);
  ASSERT_EQ(cloud.intensity.size(), cloud.size());
  for (std::size_t i = 0; i < cloud.size(); i += 97) {
    EXPECT_LT(world.distance_to_surface(cloud.points[i].cast<double>()), 1e-4);
    EXPECT_TRUE(world.bounds().contains(cloud.points[i].cast<double>()));
  }
  // Halving the spacing gives about four times the points.
  const double ratio = static_cast<double>(world.sample_surfaces(0.1).size()) / cloud.size();
  EXPECT_NEAR(ratio, 4.0, 0.6);
  // No sample lies below the floor or at the bottom of a box standing on it.
  for (const auto& p : cloud.points) ASSERT_GT(p.z(), -1e-4);
  std::size_t on_floor = 0;
  for (const auto& p : cloud.points) on_floor += std::abs(p.z()) < 1e-4;
  const Eigen::AlignedBox3d b = world.bounds();
  const double floor_cells = b.sizes().x() * b.sizes().y() / 0.04;
  EXPECT_LT(on_floor, floor_cells * 1.001) << "box bottoms on the floor were sampled";
}

}  // namespace
}  // namespace vilslam::sim
