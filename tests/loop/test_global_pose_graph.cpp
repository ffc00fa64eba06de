// The global pose graph of the running system (bounded corrections on anchors, docs/pose_graph.md) against the
// batch PoseGraph with every pose, on the tests' drifted square and on a long multi-loop drive.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <utility>
#include <vector>

#include "loop/block_route.h"
#include "loop/global_pose_graph.h"
#include "loop/odometry_chain.h"
#include "loop/pose_graph.h"
#include "loop/square_loop.h"

namespace vilslam {
namespace {

using test::make_square_loop;
using test::true_loop;

// Odometry factors as the batch PoseGraph's default has them (whole-step SE(3) residuals, no length-and-bearing
// form), so that the tests below compare the same problem solved with and without anchors.
loop::GlobalPoseGraphConfig square_config() {
  loop::GlobalPoseGraphConfig config;
  config.odometry_sigma_m = test::kOdometrySigmaM;
  config.odometry_sigma_rad = test::kOdometrySigmaRad;
  config.bearing_min_step_m = 0.0;
  return config;
}

// The square's poses fed as the running system does: the first pose, then the odometry increments.
loop::GlobalPoseGraph global_graph_of(const test::SquareLoop& s, const loop::GlobalPoseGraphConfig& config) {
  loop::GlobalPoseGraph graph(config);
  graph.add_first_pose(s.drifted[0].t_ns, s.drifted[0].T_W_B);
  for (const auto& c : s.odometry) graph.add_odometry(s.truth[c.to_index].t_ns, c.T_from_to);
  return graph;
}

void add_loops(loop::GlobalPoseGraph& graph, const std::vector<loop::RelativePoseConstraint>& loops) {
  for (const auto& c : loops) graph.add_loop(c.from_index, c.to_index, c.T_from_to, c.information);
}

loop::GlobalPoseGraphConfig route_config() {
  loop::GlobalPoseGraphConfig config;
  config.odometry_sigma_m = test::kRouteOdometrySigmaM;
  config.odometry_sigma_rad = test::kRouteOdometrySigmaRad;
  config.bearing_min_step_m = 0.0;  // as square_config()
  return config;
}

// The route's poses fed as the running system does, without loops.
loop::GlobalPoseGraph route_graph(const test::BlockRoute& r) {
  loop::GlobalPoseGraph graph(route_config());
  graph.add_first_pose(r.truth[0].t_ns, r.truth[0].T_W_B);
  for (std::size_t i = 1; i < r.truth.size(); ++i) graph.add_odometry(r.truth[i].t_ns, r.odometry[i]);
  return graph;
}

// The batch graph of the route's odometry and `loops`, every pose a variable, starting from `initial`.
loop::PoseGraph route_batch(const test::BlockRoute& r, const Trajectory& initial,
                            const std::vector<loop::RelativePoseConstraint>& loops) {
  loop::PoseGraph batch;
  for (const TimedPose& p : initial) batch.add_pose(p.t_ns, p.T_W_B);
  const Mat6 information = loop::information_from_sigmas(test::kRouteOdometrySigmaM, test::kRouteOdometrySigmaRad);
  for (std::size_t i = 1; i < r.truth.size(); ++i) {
    batch.add_constraint({i - 1, i, r.odometry[i], information, loop::ConstraintKind::kOdometry});
  }
  for (const auto& c : loops) batch.add_constraint(c);
  return batch;
}

struct PoseDiff {
  double max_m = 0.0;
  double max_rad = 0.0;
};

PoseDiff max_diff(const Trajectory& a, const Trajectory& b) {
  PoseDiff d;
  for (std::size_t i = 0; i < a.size(); ++i) {
    d.max_m = std::max(d.max_m, (a[i].T_W_B.translation() - b[i].T_W_B.translation()).norm());
    d.max_rad = std::max(d.max_rad, so3::log(a[i].T_W_B.quat().conjugate() * b[i].T_W_B.quat()).norm());
  }
  return d;
}

TEST(GlobalPoseGraph, LoopClosureRemovesDrift) {
  const test::SquareLoop s = make_square_loop();
  loop::GlobalPoseGraph graph = global_graph_of(s, square_config());
  add_loops(graph, {true_loop(s, 0, s.lap_poses), true_loop(s, 10, s.lap_poses + 10)});
  const loop::CorrectionSummary summary = graph.optimize();
  const double drift_before = test::end_to_start_m(s, s.drifted);
  const double drift_after = test::end_to_start_m(s, graph.trajectory());
  const double ate_before = test::position_rmse(s.drifted, s.truth);
  const double ate_after = test::position_rmse(graph.trajectory(), s.truth);
  std::printf("end-to-start drift %.4f m -> %.4f m, ATE %.4f m -> %.4f m, %zu variables, %d iterations, %.2f ms\n",
              drift_before, drift_after, ate_before, ate_after, summary.variables, summary.iterations,
              summary.solve_ms);
  EXPECT_TRUE(summary.converged);
  EXPECT_GT(drift_before, 1.0);
  EXPECT_LT(drift_after, drift_before / 50.0);
  EXPECT_LT(ate_after, ate_before / 5.0);
  EXPECT_LT(summary.variables, s.truth.size() / 5);
  EXPECT_EQ(summary.moved_poses, s.truth.size() - 1);
  EXPECT_EQ(graph.pose(0).translation(), s.drifted[0].T_W_B.translation());
}

// The anchors' solution and the chains' interiors against the batch solve with every pose: exact with one anchor
// per pose; otherwise the difference is second order in a chain's correction, here (1.2 degrees of yaw drift a
// metre) 0.26 / 1.09 / 3.87 mm at spacings 5 / 10 (default) / 20, 30 mm with only the loop ends as anchors.
TEST(GlobalPoseGraph, MatchesBatchOnSquare) {
  const test::SquareLoop s = make_square_loop();
  const std::vector<loop::RelativePoseConstraint> loops = {true_loop(s, 0, s.lap_poses),
                                                           true_loop(s, 10, s.lap_poses + 10)};
  loop::PoseGraph batch = test::graph_of(s, loops);
  batch.optimize();
  const struct {
    std::size_t spacing;
    double tolerance_m;
    double tolerance_rad;
  } cases[] = {{1, 1e-6, 1e-8}, {5, 0.5e-3, 5e-6}, {10, 1.5e-3, 1.5e-5}, {20, 5e-3, 6e-5}, {1000, 40e-3, 1e-3}};
  for (const auto& c : cases) {
    loop::GlobalPoseGraphConfig config = square_config();
    config.anchor_spacing = c.spacing;
    loop::GlobalPoseGraph graph = global_graph_of(s, config);
    add_loops(graph, loops);
    const loop::CorrectionSummary summary = graph.optimize();
    const PoseDiff d = max_diff(graph.trajectory(), batch.poses());
    std::printf("anchor spacing %4zu: %2zu variables, max difference to batch %.4f mm, %.3g rad\n", c.spacing,
                summary.variables, 1e3 * d.max_m, d.max_rad);
    EXPECT_LT(d.max_m, c.tolerance_m) << c.spacing;
    EXPECT_LT(d.max_rad, c.tolerance_rad) << c.spacing;
  }
}

// 3000 poses (6 laps of a 250 m block, ~1 % odometry drift), a loop a lap, corrected as each loop arrives,
// against one batch solve of all factors at the end.
TEST(GlobalPoseGraph, MatchesBatchOnLongMultiLoopRoute) {
  const test::BlockRoute r = test::make_block_route(3000);
  loop::GlobalPoseGraph graph(route_config());
  graph.add_first_pose(r.truth[0].t_ns, r.truth[0].T_W_B);
  std::size_t next_loop = 0;
  std::size_t max_variables = 0;
  for (std::size_t i = 1; i < r.truth.size(); ++i) {
    graph.add_odometry(r.truth[i].t_ns, r.odometry[i]);
    for (; next_loop < r.loops.size() && r.loops[next_loop].to_index == i; ++next_loop) {
      add_loops(graph, {r.loops[next_loop]});
      const loop::CorrectionSummary summary = graph.optimize();
      EXPECT_TRUE(summary.converged) << i;
      max_variables = std::max(max_variables, summary.variables);
    }
  }
  ASSERT_EQ(next_loop, r.loops.size());

  const Trajectory drifted = test::dead_reckoning(r);
  loop::PoseGraph batch = route_batch(r, drifted, r.loops);
  batch.optimize();
  const PoseDiff d = max_diff(graph.trajectory(), batch.poses());
  const double ate_drifted = test::position_rmse(drifted, r.truth);
  const double ate_batch = test::position_rmse(batch.poses(), r.truth);
  const double ate_global = test::position_rmse(graph.trajectory(), r.truth);
  std::printf("%zu loops, at most %zu variables; ATE odometry %.3f m, batch %.3f m, global %.3f m; max difference "
              "to batch %.3f mm, %.3g rad\n",
              r.loops.size(), max_variables, ate_drifted, ate_batch, ate_global, 1e3 * d.max_m, d.max_rad);
  EXPECT_LT(ate_batch, ate_drifted / 2.0);
  EXPECT_LT(d.max_m, 0.1e-3);
  EXPECT_LT(d.max_rad, 2e-6);
}

TEST(GlobalPoseGraph, AddOdometryComposesFromCorrectedPose) {
  const test::SquareLoop s = make_square_loop();
  loop::GlobalPoseGraph graph = global_graph_of(s, square_config());
  add_loops(graph, {true_loop(s, 0, s.lap_poses)});
  graph.optimize();
  const std::size_t last = graph.size() - 1;
  const SE3 T_prev_cur = s.odometry.back().T_from_to;
  const std::size_t index = graph.add_odometry(s.truth.back().t_ns + 100'000'000, T_prev_cur);
  EXPECT_EQ(index, last + 1);
  const SE3 expected = graph.pose(last) * T_prev_cur;
  EXPECT_EQ(graph.pose(index).translation(), expected.translation());
  EXPECT_EQ(graph.pose(index).quat().coeffs(), expected.quat().coeffs());
  // Not the dead-reckoned pose: the correction moved the previous pose by decimetres.
  EXPECT_GT((graph.pose(index).translation() - (s.drifted.back().T_W_B * T_prev_cur).translation()).norm(), 0.1);
}

TEST(GlobalPoseGraph, RobustLossDownWeightsWrongLoop) {
  const test::SquareLoop s = make_square_loop();
  loop::RelativePoseConstraint wrong = true_loop(s, 20, 60);  // two corners 14 m apart claimed to coincide
  wrong.T_from_to = SE3::identity();
  const std::vector<loop::RelativePoseConstraint> loops = {true_loop(s, 0, s.lap_poses),
                                                           true_loop(s, 10, s.lap_poses + 10), wrong};
  loop::GlobalPoseGraphConfig huber = square_config();
  loop::GlobalPoseGraphConfig squared = square_config();
  squared.loop_loss = loop::RobustLoss::kNone;
  loop::GlobalPoseGraph clean_graph = global_graph_of(s, huber);
  loop::GlobalPoseGraph huber_graph = global_graph_of(s, huber);
  loop::GlobalPoseGraph squared_graph = global_graph_of(s, squared);
  add_loops(clean_graph, {loops[0], loops[1]});
  add_loops(huber_graph, loops);
  add_loops(squared_graph, loops);
  clean_graph.optimize();
  huber_graph.optimize();
  squared_graph.optimize();
  const double ate_clean = test::position_rmse(clean_graph.trajectory(), s.truth);
  const double ate_huber = test::position_rmse(huber_graph.trajectory(), s.truth);
  const double ate_squared = test::position_rmse(squared_graph.trajectory(), s.truth);
  std::printf("ATE with a wrong loop: Huber %.4f m, squared %.4f m (without it %.4f m)\n", ate_huber, ate_squared,
              ate_clean);
  EXPECT_LT(ate_huber, 2.0 * ate_clean);
  EXPECT_GT(ate_squared, 10.0 * ate_huber);
}

TEST(GlobalPoseGraph, RejectsBadInput) {
  loop::GlobalPoseGraph graph;
  EXPECT_THROW(graph.add_odometry(0, SE3()), std::logic_error);
  graph.add_first_pose(0, SE3());
  EXPECT_THROW(graph.add_first_pose(1, SE3()), std::logic_error);
  graph.add_odometry(1, SE3());
  EXPECT_THROW(graph.add_loop(0, 2, SE3(), Mat6::Identity()), std::invalid_argument);
  EXPECT_THROW(graph.add_loop(1, 1, SE3(), Mat6::Identity()), std::invalid_argument);
  Mat6 not_positive = Mat6::Identity();
  not_positive(3, 3) = -1.0;
  EXPECT_THROW(graph.add_loop(0, 1, SE3(), not_positive), std::invalid_argument);
  Mat6 not_symmetric = Mat6::Identity();
  not_symmetric(0, 1) = 0.5;
  EXPECT_THROW(graph.add_loop(0, 1, SE3(), not_symmetric), std::invalid_argument);
  EXPECT_THROW(graph.pose(2), std::out_of_range);
  EXPECT_THROW(graph.set_up_direction(2, Vec3::UnitZ()), std::invalid_argument);
  EXPECT_THROW(graph.set_up_direction(1, Vec3(0.0, std::nan(""), 1.0)), std::invalid_argument);
  EXPECT_THROW(graph.set_up_direction(1, Vec3::Zero()), std::invalid_argument);
  EXPECT_THROW(graph.set_up_direction(1, Vec3::UnitZ(), -0.1), std::invalid_argument);
  EXPECT_THROW(graph.set_up_direction(1, Vec3::UnitZ(), std::nan("")), std::invalid_argument);
  // Nothing was added, so there is nothing to correct.
  EXPECT_EQ(graph.optimize().variables, 0u);
  loop::GlobalPoseGraphConfig bad;
  bad.odometry_sigma_m = 0.0;
  EXPECT_THROW(loop::GlobalPoseGraph{bad}, std::invalid_argument);
  bad = {};
  bad.anchor_spacing = 0;
  EXPECT_THROW(loop::GlobalPoseGraph{bad}, std::invalid_argument);
  bad = {};
  bad.tilt_sigma_rad = -0.01;
  EXPECT_THROW(loop::GlobalPoseGraph{bad}, std::invalid_argument);
}

TEST(GlobalPoseGraph, TwoRunsAreBitIdentical) {
  const test::BlockRoute r = test::make_block_route(1600);
  auto run = [&r] {
    loop::GlobalPoseGraph graph = route_graph(r);
    add_loops(graph, r.loops);
    graph.optimize();
    return graph.trajectory();
  };
  const Trajectory a = run();
  const Trajectory b = run();
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    ASSERT_EQ(std::memcmp(a[i].T_W_B.quat().coeffs().data(), b[i].T_W_B.quat().coeffs().data(), 4 * sizeof(double)), 0);
    ASSERT_EQ(std::memcmp(a[i].T_W_B.translation().data(), b[i].T_W_B.translation().data(), 3 * sizeof(double)), 0);
  }
  EXPECT_GT((a.back().T_W_B.translation() - test::dead_reckoning(r).back().T_W_B.translation()).norm(), 0.1);
}

// A loop whose span no older loop crosses moves only the poses after its lower end (the window's fixed first
// pose is a cut of the graph), and the result is still the batch solution.
TEST(GlobalPoseGraph, CorrectionMovesOnlyThePosesAfterTheLastCut) {
  const test::BlockRoute r = test::make_block_route(1600);
  ASSERT_GE(r.loops.size(), 2u);
  loop::GlobalPoseGraph graph = route_graph(r);
  add_loops(graph, {r.loops[0]});
  graph.optimize();
  const Trajectory before = graph.trajectory();
  // A loop inside the last lap, after every older loop's span.
  const std::size_t u = std::max(r.loops[0].to_index, r.truth.size() - r.lap_poses) + 10;
  const std::size_t v = r.truth.size() - 5;
  loop::RelativePoseConstraint late{u, v, r.truth[u].T_W_B.inverse() * r.truth[v].T_W_B,
                                    loop::information_from_sigmas(test::kRouteLoopSigmaM, test::kRouteLoopSigmaRad),
                                    loop::ConstraintKind::kLoop};
  add_loops(graph, {late});
  const loop::CorrectionSummary summary = graph.optimize();
  EXPECT_EQ(summary.moved_poses, r.truth.size() - 1 - u);
  for (std::size_t i = 0; i <= u; ++i) {
    ASSERT_EQ(std::memcmp(before[i].T_W_B.translation().data(), graph.pose(i).translation().data(), 3 * sizeof(double)),
              0)
        << i;
  }
  EXPECT_GT((before.back().T_W_B.translation() - graph.pose(r.truth.size() - 1).translation()).norm(), 0.01);

  loop::PoseGraph batch = route_batch(r, before, {r.loops[0], late});
  batch.optimize();
  const PoseDiff d = max_diff(graph.trajectory(), batch.poses());
  std::printf("window of %zu poses, %zu variables; max difference to batch %.3f mm\n", summary.moved_poses,
              summary.variables, 1e3 * d.max_m);
  EXPECT_LT(d.max_m, 0.1e-3);
}

// A straight route of 40 steps of 0.5 m along x whose odometry is 1 cm short in every step; steps 21..40 were
// registered with their x axis degenerate (a corridor). A loop measuring the true end-to-end motion then
// lengthens the degenerate half: its steps take the misclosure in proportion to their variance along x.
TEST(GlobalPoseGraph, DegenerateStepsTakeTheCorrectionAlongTheirDirection) {
  for (const bool with_directions : {false, true}) {
    loop::GlobalPoseGraphConfig config;
    config.anchor_spacing = 4;
    loop::GlobalPoseGraph graph(config);
    graph.add_first_pose(0, SE3());
    const Vec6 along_x = (Vec6() << 1, 0, 0, 0, 0, 0).finished();
    for (int i = 1; i <= 40; ++i) {
      const bool degenerate = with_directions && i > 20;
      graph.add_odometry(i * 100'000'000LL, SE3(Quat::Identity(), Vec3(0.49, 0, 0)),
                         degenerate ? std::vector<Vec6>{along_x} : std::vector<Vec6>{});
    }
    graph.add_loop(0, 40, SE3(Quat::Identity(), Vec3(20.0, 0, 0)), loop::information_from_sigmas(1e-4, 1e-5));
    graph.optimize();
    const double first_half_m = graph.pose(20).translation().x() - 20 * 0.49;
    const double total_m = graph.pose(40).translation().x() - 40 * 0.49;
    EXPECT_NEAR(total_m, 0.4, 1e-3);
    // Variances per step: 0.01^2 each without directions (half each), 0.01^2 vs 0.01^2 + 0.1^2 with.
    const double expected_share = with_directions ? 1.0 / (1.0 + 101.0) : 0.5;
    EXPECT_NEAR(first_half_m / total_m, expected_share, 0.01) << (with_directions ? "degenerate" : "uniform");
  }
}

// A straight 20 m route whose odometry pitches 1 deg in steps 3-12 (a registration's wobble), every pose's measured
// up direction level (sigma measured_sigma_rad), and a loop from pose 2 to the end that says the route is level.
loop::GlobalPoseGraph wobble_route_graph(const loop::GlobalPoseGraphConfig& config, double wobble_rad,
                                         double measured_sigma_rad) {
  loop::GlobalPoseGraph graph(config);
  graph.add_first_pose(0, SE3());
  for (int i = 1; i <= 40; ++i) {
    const bool wobbling = i >= 3 && i <= 12;
    const Quat step_rotation = wobbling ? Quat(Eigen::AngleAxisd(wobble_rad / 10.0, Vec3::UnitY())) : Quat::Identity();
    graph.add_odometry(i * 100'000'000LL, SE3(step_rotation, Vec3(0.5, 0, 0)));
  }
  for (std::size_t i = 0; i < graph.size(); ++i) graph.set_up_direction(i, Vec3::UnitZ(), measured_sigma_rad);
  graph.add_loop(2, 40, SE3(Quat::Identity(), Vec3(19.0, 0, 0)), loop::information_from_sigmas(0.01, 0.001));
  return graph;
}

double graph_max_tilt_rad(const loop::GlobalPoseGraph& graph) {
  double max_rad = 0.0;
  for (std::size_t i = 0; i < graph.size(); ++i) {
    const Vec3 up_L = graph.pose(i).rotation().transpose() * Vec3::UnitZ();
    max_rad = std::max(max_rad, std::acos(std::clamp(up_L.z(), -1.0, 1.0)));
  }
  return max_rad;
}

// A level straight route of 40 steps of 0.5 m whose odometry pitched by 1 degree over steps 3-12 (the outdoor
// mapper's start wobble, docs/odometry.md) and stayed pitched. A loop from pose 2, before the error, measures the
// true motion to pose 40. Without tilt factors the graph spreads the 1 degree over the whole route, so mid-route
// poses stay more than half a degree off. With the VIO's up direction measured at every pose (level here) every
// pose comes back to within a quarter of the wobble (the odometry's own stiffness keeps the rest: 0.18 degrees).
// Up directions whose own sigma is 3 degrees (a VIO that has just started again) hold nothing.
TEST(GlobalPoseGraph, TiltFactorsKeepTheRouteLevelThroughALoop) {
  const double wobble_rad = 1.0 * M_PI / 180.0;
  for (const auto& [tilt_sigma_rad, measured_sigma_rad] :
       std::vector<std::pair<double, double>>{{0.0, 0.0}, {0.002, 0.0}, {0.002, 0.05}}) {
    loop::GlobalPoseGraphConfig config;
    config.anchor_spacing = 4;
    config.tilt_sigma_rad = tilt_sigma_rad;
    config.tilt_final_only = false;  // the tilt factors in the correction itself
    loop::GlobalPoseGraph graph = wobble_route_graph(config, wobble_rad, measured_sigma_rad);
    graph.optimize();
    const double tilt_rad = graph_max_tilt_rad(graph);
    std::printf("tilt sigma %.3f rad, measured %.3f rad: max tilt %.3f deg, end height %.4f m\n", tilt_sigma_rad,
                measured_sigma_rad, tilt_rad * 180.0 / M_PI, graph.pose(40).translation().z());
    if (tilt_sigma_rad > 0.0 && measured_sigma_rad == 0.0) {
      EXPECT_LT(tilt_rad, 0.25 * wobble_rad);
      EXPECT_NEAR(graph.pose(40).translation().z(), 0.0, 0.01);
    } else {
      EXPECT_GT(tilt_rad, 0.5 * wobble_rad);
    }
  }
}

// tilt_final_only (the default): the correction fed back to the mapper keeps the odometry's tilt (as without tilt
// factors), and the final solve levels the route as a correction with the tilt factors does; without the option the
// final solve changes nothing.
TEST(GlobalPoseGraph, WithTiltFinalOnlyTheCorrectionKeepsTheTiltAndTheFinalSolveLevels) {
  const double wobble_rad = 1.0 * M_PI / 180.0;
  loop::GlobalPoseGraphConfig config;
  config.anchor_spacing = 4;
  config.tilt_sigma_rad = 0.002;
  config.tilt_final_only = false;
  loop::GlobalPoseGraph levelled = wobble_route_graph(config, wobble_rad, 0.0);
  levelled.optimize();
  const Trajectory corrected = levelled.trajectory();
  EXPECT_EQ(levelled.optimize_final().variables, 0u);
  EXPECT_EQ(max_diff(levelled.trajectory(), corrected).max_m, 0.0);

  config.tilt_final_only = true;
  loop::GlobalPoseGraph final_only = wobble_route_graph(config, wobble_rad, 0.0);
  final_only.optimize();
  EXPECT_GT(graph_max_tilt_rad(final_only), 0.5 * wobble_rad);
  EXPECT_GT(final_only.optimize_final().variables, 0u);
  EXPECT_LT(graph_max_tilt_rad(final_only), 0.25 * wobble_rad);
  EXPECT_NEAR(final_only.pose(40).translation().z(), 0.0, 0.01);
  EXPECT_LT(max_diff(final_only.trajectory(), corrected).max_m, 0.01);
}

// Why a pitched mount shortens a corridor (docs/pose_graph.md, "Length and bearing of a step"): an out-and-back route,
// level, 40 m each way, its measured up directions through a LiDAR mount 0.5 deg off in pitch, every straight step
// degenerate along its axis (a corridor). Tilt factors that hold a pose 0.5 deg
// off the odometry's pitch leave each level step a vertical residual |t| sin(0.5 deg), and shortening the step shrinks
// it; along a degenerate axis length costs (0.01^2 + 0.1^2) / 0.01^2 = 101 times less, and both legs shrink alike, so
// the loop between the ends does not see it. Without the added sigma, or with the steps compared as length and
// bearing (bearing_min_step_m), the legs keep their length.
TEST(GlobalPoseGraph, APitchAgainstTheOdometryShortensDegenerateLegs) {
  const Mat3 mount_error = so3::exp(Vec3(0.0, 0.5 * M_PI / 180.0, 0.0));
  const int leg = 200;  // 40 m each way
  const Vec6 along_x = (Vec6() << 1, 0, 0, 0, 0, 0).finished();
  struct Case {
    double degenerate_sigma;
    double bearing_min_step_m;
  };
  for (const Case c : {Case{0.1, 0.0}, Case{0.0, 0.0}, Case{0.1, 0.05}}) {
    loop::GlobalPoseGraphConfig config;
    config.degenerate_sigma = c.degenerate_sigma;
    config.bearing_min_step_m = c.bearing_min_step_m;
    config.tilt_final_only = false;  // the tilt factors in the correction itself
    loop::GlobalPoseGraph graph(config);
    graph.add_first_pose(0, SE3());
    graph.set_up_direction(0, mount_error.transpose() * Vec3::UnitZ());
    for (int i = 1; i <= 2 * leg + 1; ++i) {
      const bool turn = i == leg + 1;
      graph.add_odometry(i * 100'000'000LL,
                         turn ? SE3(so3::exp_quat(Vec3(0, 0, M_PI)), Vec3::Zero()) : SE3(Quat::Identity(), Vec3(0.2, 0, 0)),
                         turn ? std::vector<Vec6>{} : std::vector<Vec6>{along_x});
      graph.set_up_direction(graph.size() - 1, mount_error.transpose() * Vec3::UnitZ());
    }
    graph.add_loop(0, graph.size() - 1, SE3(so3::exp_quat(Vec3(0, 0, M_PI)), Vec3::Zero()),
                   loop::information_from_sigmas(0.01, 0.001));
    graph.optimize();
    const double out_m = graph.pose(leg).translation().x() - graph.pose(0).translation().x();
    const double back_m = graph.pose(leg + 1).translation().x() - graph.pose(2 * leg + 1).translation().x();
    std::printf("degenerate sigma %.2f, bearing from %.2f m: legs %.4f and %.4f m off\n", c.degenerate_sigma,
                c.bearing_min_step_m, out_m - 0.2 * leg, back_m - 0.2 * leg);
    if (c.degenerate_sigma > 0.0 && c.bearing_min_step_m == 0.0) {
      EXPECT_LT(out_m - 0.2 * leg, -0.1);
      EXPECT_LT(back_m - 0.2 * leg, -0.1);
    } else {
      EXPECT_NEAR(out_m, 0.2 * leg, 0.01);
      EXPECT_NEAR(back_m, 0.2 * leg, 0.01);
    }
  }
}

// The composed covariance is the first-order propagation: sum_i J_i Sigma J_i^T with J_i the derivative of the
// chain's error Log(Z_ab^-1 prod_j Z_j Exp(eps_j)) by eps_i, here by central differences.
// Re-localization in a saved map (docs/loop.md, "Map reuse"): the drifted square fed in a frame of its own,
// moved into the map's by transform(), then held by loops from three map poses (fixed, not graph poses) to poses
// that are not on the anchor spacing: the drift goes, and each map loop holds the very pose it names.
TEST(GlobalPoseGraph, MapLoopsBringTheRunIntoTheMapsFrame) {
  const test::SquareLoop s = make_square_loop();
  const SE3 T_run_map(so3::exp_quat(Vec3(0.01, -0.02, 2.0)), Vec3(3.0, -4.0, 0.5));
  loop::GlobalPoseGraph graph(square_config());
  graph.add_first_pose(s.drifted[0].t_ns, T_run_map * s.drifted[0].T_W_B);
  for (const auto& c : s.odometry) graph.add_odometry(s.truth[c.to_index].t_ns, c.T_from_to);
  graph.transform(T_run_map.inverse());
  EXPECT_LT(max_diff(graph.trajectory(), s.drifted).max_m, 1e-9);
  const Mat6 information = loop::information_from_sigmas(test::kLoopSigmaM, test::kLoopSigmaRad);
  const std::vector<std::size_t> held = {13, 47, s.lap_poses + 7};
  for (std::size_t k : held) {
    // The map's key scan of the place, 0.3 m to the side and turned a little, and the loop it gives.
    const SE3 T_map_Lu = s.truth[k].T_W_B * SE3(so3::exp_quat(Vec3(0, 0, 0.1)), Vec3(0, 0.3, 0));
    graph.add_map_loop(T_map_Lu, k, T_map_Lu.inverse() * s.truth[k].T_W_B, information);
  }
  EXPECT_EQ(graph.map_loops(), held.size());
  const loop::CorrectionSummary summary = graph.optimize();
  EXPECT_TRUE(summary.converged);
  EXPECT_EQ(summary.moved_poses, s.truth.size());  // the first pose too: the map loops hold the gauge
  const double ate_before = test::position_rmse(s.drifted, s.truth);
  const double ate_after = test::position_rmse(graph.trajectory(), s.truth);
  std::printf("ATE %.4f m -> %.4f m with %zu map loops\n", ate_before, ate_after, held.size());
  EXPECT_LT(ate_after, ate_before / 5.0);
  for (std::size_t k : held) EXPECT_LT((graph.pose(k).translation() - s.truth[k].T_W_B.translation()).norm(), 0.02) << k;
}

// A map loop that only stood in (after a reset, one verified from a guess): 0.3 m off, it pulls the run; removed
// once a better one is there, the next correction forgets it. Removing every map loop is refused (they hold the
// gauge), as is a position that does not exist.
TEST(GlobalPoseGraph, RemovedMapLoopsNoLongerPull) {
  const test::SquareLoop s = make_square_loop();
  loop::GlobalPoseGraph graph = global_graph_of(s, square_config());
  const Mat6 information = loop::information_from_sigmas(test::kLoopSigmaM, test::kLoopSigmaRad);
  const std::size_t k = 13;
  const SE3 T_map_Lu = s.truth[k].T_W_B;
  const SE3 off(Mat3::Identity(), Vec3(0.3, 0, 0));
  graph.add_map_loop(T_map_Lu, k, off, information);                   // the stand-in, 0.3 m off
  graph.add_map_loop(T_map_Lu, k + 1, T_map_Lu.inverse() * s.truth[k + 1].T_W_B, information);  // right
  graph.optimize();
  const double pulled_m = (graph.pose(k).translation() - s.truth[k].T_W_B.translation()).norm();
  graph.remove_map_loops({0});
  EXPECT_EQ(graph.map_loops(), 1u);
  graph.optimize();
  const double held_m = (graph.pose(k).translation() - s.truth[k].T_W_B.translation()).norm();
  std::printf("pose %zu: %.3f m off with the stand-in, %.3f m without\n", k, pulled_m, held_m);
  EXPECT_GT(pulled_m, 0.1);
  EXPECT_LT(held_m, 0.02);
  EXPECT_THROW(graph.remove_map_loops({0}), std::invalid_argument);
  EXPECT_THROW(graph.remove_map_loops({3}), std::invalid_argument);
}

TEST(OdometryChain, CovarianceMatchesNumericJacobians) {
  const test::BlockRoute r = test::make_block_route(40);
  const std::size_t a = 5;
  const std::size_t b = 35;
  const Mat6 sigma = loop::information_from_sigmas(0.01, 0.002).inverse();
  const loop::ComposedChain chain = loop::compose_chain(r.odometry, loop::Mat6List(r.odometry.size(), sigma), a, b);
  Mat6 numeric = Mat6::Zero();
  constexpr double kH = 1e-6;
  for (std::size_t i = a + 1; i <= b; ++i) {
    Mat6 J;
    for (int k = 0; k < 6; ++k) {
      Vec6 sides[2];
      for (int s = 0; s < 2; ++s) {
        SE3 T = SE3();
        for (std::size_t j = a + 1; j <= b; ++j) {
          Vec6 eps = Vec6::Zero();
          if (j == i) eps[k] = s == 0 ? kH : -kH;
          T = T * r.odometry[j] * SE3::exp(eps);
        }
        sides[s] = (chain.T_a_b.inverse() * T).log();
      }
      J.col(k) = (sides[0] - sides[1]) / (2.0 * kH);
    }
    numeric += J * sigma * J.transpose();
  }
  const SE3 T_direct = [&] {
    SE3 T = SE3();
    for (std::size_t j = a + 1; j <= b; ++j) T = T * r.odometry[j];
    return T;
  }();
  EXPECT_LT((chain.T_a_b.inverse() * T_direct).log().norm(), 1e-12);
  EXPECT_LT((chain.covariance - numeric).norm(), 1e-6 * numeric.norm());
}

// With ends that agree with the odometry, the interior is the odometry composition; with a misclosure, the
// interior poses take the conditional mean of the chain's error (eq. C2): here a pure translation misclosure
// on a straight chain with translation-only noise is spread in proportion to the index.
TEST(OdometryChain, InteriorFollowsTheEnds) {
  std::vector<SE3> steps(11, SE3(Quat::Identity(), Vec3(0.5, 0, 0)));
  Trajectory poses(11);
  poses[0].T_W_B = SE3();
  for (std::size_t j = 1; j < poses.size(); ++j) poses[j].T_W_B = poses[j - 1].T_W_B * steps[j];
  const Mat6 sigma = loop::information_from_sigmas(0.01, 1e-6).inverse();
  Trajectory consistent = poses;
  for (std::size_t j = 1; j < 10; ++j) consistent[j].T_W_B = SE3(Quat::Identity(), Vec3(7, 7, 7));
  const loop::Mat6List covariances(steps.size(), sigma);
  loop::correct_chain_interior(steps, covariances, 0, 10, consistent);
  for (std::size_t j = 0; j < poses.size(); ++j) {
    EXPECT_LT((consistent[j].T_W_B.translation() - poses[j].T_W_B.translation()).norm(), 1e-12) << j;
  }
  Trajectory moved = poses;
  moved[10].T_W_B.translation() += Vec3(0, 1.0, 0);
  loop::correct_chain_interior(steps, covariances, 0, 10, moved);
  for (std::size_t j = 1; j < 10; ++j) {
    const Vec3 expected = poses[j].T_W_B.translation() + Vec3(0, 0.1 * static_cast<double>(j), 0);
    EXPECT_LT((moved[j].T_W_B.translation() - expected).norm(), 1e-6) << j;
  }
}

}  // namespace
}  // namespace vilslam
