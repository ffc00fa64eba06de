// The global pose graph on a synthetic square loop with biased odometry (tests/loop/square_loop.h).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <stdexcept>

#include "loop/pose_graph.h"
#include "loop/square_loop.h"

namespace vilslam {
namespace {

using test::make_square_loop;
using test::true_loop;

TEST(PoseGraph, LoopClosureRemovesDrift) {
  const test::SquareLoop s = make_square_loop();
  loop::PoseGraph graph = test::graph_of(s, {true_loop(s, 0, s.lap_poses), true_loop(s, 10, s.lap_poses + 10)});
  const loop::PoseGraphSummary summary = graph.optimize();

  const double drift_before = test::end_to_start_m(s, s.drifted);
  const double drift_after = test::end_to_start_m(s, graph.poses());
  const double ate_before = test::position_rmse(s.drifted, s.truth);
  const double ate_after = test::position_rmse(graph.poses(), s.truth);
  std::printf("end-to-start drift %.4f m -> %.4f m, ATE %.4f m -> %.4f m, %d iterations, cost %.1f -> %.3f, "
              "loop residual max %.3f sigma\n",
              drift_before, drift_after, ate_before, ate_after, summary.iterations, summary.initial_cost,
              summary.final_cost, summary.loop.whitened_max);
  EXPECT_TRUE(summary.converged);
  EXPECT_GT(drift_before, 1.0);
  EXPECT_LT(drift_after, drift_before / 50.0);
  EXPECT_LT(ate_after, ate_before / 5.0);
  EXPECT_LT(summary.final_cost, summary.initial_cost);
  // The biased odometry absorbs the loop: the loops end inside the quadratic region of the Huber loss.
  EXPECT_LT(summary.loop.whitened_max, 1.0);
  EXPECT_EQ(summary.odometry.count, s.odometry.size());
  EXPECT_EQ(summary.loop.count, 2u);
  // The first pose is the gauge.
  EXPECT_EQ(graph.poses()[0].T_W_B.translation(), s.drifted[0].T_W_B.translation());
}

TEST(PoseGraph, RobustLossDownWeightsWrongLoop) {
  const test::SquareLoop s = make_square_loop();
  // Pose 20 (corner at x = 10) and pose 60 (corner at y = 10) are 14 m apart; this loop claims they coincide.
  loop::RelativePoseConstraint wrong = true_loop(s, 20, 60);
  wrong.T_from_to = SE3::identity();
  const std::vector<loop::RelativePoseConstraint> loops = {true_loop(s, 0, s.lap_poses),
                                                           true_loop(s, 10, s.lap_poses + 10), wrong};
  loop::PoseGraphOptions robust;
  robust.loop_loss = loop::RobustLoss::kHuber;
  loop::PoseGraphOptions squared;
  squared.loop_loss = loop::RobustLoss::kNone;
  loop::PoseGraph clean_graph = test::graph_of(s, {loops[0], loops[1]});
  loop::PoseGraph robust_graph = test::graph_of(s, loops);
  loop::PoseGraph squared_graph = test::graph_of(s, loops);
  const loop::PoseGraphSummary robust_summary = robust_graph.optimize(robust);
  squared_graph.optimize(squared);
  clean_graph.optimize(robust);

  const double ate_robust = test::position_rmse(robust_graph.poses(), s.truth);
  const double ate_squared = test::position_rmse(squared_graph.poses(), s.truth);
  const double ate_clean = test::position_rmse(clean_graph.poses(), s.truth);
  std::printf("ATE with a wrong loop: Huber %.4f m, squared loss %.4f m (without it %.4f m); worst loop residual "
              "%.1f sigma\n",
              ate_robust, ate_squared, ate_clean, robust_summary.loop.whitened_max);
  EXPECT_LT(ate_robust, 2.0 * ate_clean);
  EXPECT_GT(ate_squared, 10.0 * ate_robust);
  // The outlier keeps its large residual instead of bending the trajectory.
  EXPECT_GT(robust_summary.loop.translation_max_m, 10.0);
}

TEST(PoseGraph, CauchyIgnoresWrongLoopAddedAfterClosing) {
  const test::SquareLoop s = make_square_loop();
  loop::PoseGraph graph = test::graph_of(s, {true_loop(s, 0, s.lap_poses), true_loop(s, 10, s.lap_poses + 10)});
  graph.optimize();
  const double ate_closed = test::position_rmse(graph.poses(), s.truth);
  loop::RelativePoseConstraint wrong = true_loop(s, 20, 60);
  wrong.T_from_to = SE3::identity();
  graph.add_constraint(wrong);
  loop::PoseGraphOptions cauchy;
  cauchy.loop_loss = loop::RobustLoss::kCauchy;
  graph.optimize(cauchy);
  const double ate_cauchy = test::position_rmse(graph.poses(), s.truth);
  std::printf("ATE after closing %.4f m, after adding a wrong loop and re-optimizing with Cauchy %.4f m\n",
              ate_closed, ate_cauchy);
  EXPECT_LT(std::abs(ate_cauchy - ate_closed), 0.01);
}

TEST(PoseGraph, TwoRunsAreBitIdentical) {
  const test::SquareLoop s = make_square_loop();
  const std::vector<loop::RelativePoseConstraint> loops = {true_loop(s, 0, s.lap_poses)};
  loop::PoseGraph a = test::graph_of(s, loops);
  loop::PoseGraph b = test::graph_of(s, loops);
  a.optimize();
  b.optimize();
  for (std::size_t i = 0; i < s.truth.size(); ++i) {
    const SE3& Ta = a.poses()[i].T_W_B;
    const SE3& Tb = b.poses()[i].T_W_B;
    ASSERT_EQ(std::memcmp(Ta.quat().coeffs().data(), Tb.quat().coeffs().data(), 4 * sizeof(double)), 0) << i;
    ASSERT_EQ(std::memcmp(Ta.translation().data(), Tb.translation().data(), 3 * sizeof(double)), 0) << i;
  }
}

TEST(PoseGraph, IncrementalReoptimizationMatchesBatch) {
  const test::SquareLoop s = make_square_loop();
  const std::size_t half = s.truth.size() / 2;
  loop::PoseGraph incremental;
  for (std::size_t i = 0; i < half; ++i) incremental.add_pose(s.drifted[i].t_ns, s.drifted[i].T_W_B);
  for (std::size_t i = 0; i + 1 < half; ++i) incremental.add_constraint(s.odometry[i]);
  incremental.optimize();
  for (std::size_t i = half; i < s.truth.size(); ++i) incremental.add_pose(s.drifted[i].t_ns, s.drifted[i].T_W_B);
  for (std::size_t i = half - 1; i < s.odometry.size(); ++i) incremental.add_constraint(s.odometry[i]);
  incremental.add_constraint(true_loop(s, 0, s.lap_poses));
  incremental.optimize();

  loop::PoseGraph batch = test::graph_of(s, {true_loop(s, 0, s.lap_poses)});
  batch.optimize();
  double max_diff_m = 0.0;
  for (std::size_t i = 0; i < s.truth.size(); ++i) {
    max_diff_m = std::max(
        max_diff_m, (incremental.poses()[i].T_W_B.translation() - batch.poses()[i].T_W_B.translation()).norm());
  }
  EXPECT_LT(max_diff_m, 1e-6);
  EXPECT_LT(test::end_to_start_m(s, incremental.poses()), 0.05);
}

TEST(PoseGraph, RejectsBadConstraints) {
  loop::PoseGraph graph;
  graph.add_pose(0, SE3());
  graph.add_pose(1, SE3());
  loop::RelativePoseConstraint c{0, 2, SE3(), Mat6::Identity(), loop::ConstraintKind::kLoop};
  EXPECT_THROW(graph.add_constraint(c), std::invalid_argument);
  c.to_index = 0;
  EXPECT_THROW(graph.add_constraint(c), std::invalid_argument);
  c.to_index = 1;
  c.information(2, 2) = -1.0;
  EXPECT_THROW(graph.add_constraint(c), std::invalid_argument);
  EXPECT_THROW(loop::information_from_sigmas(0.0, 0.1), std::invalid_argument);
  EXPECT_THROW(graph.add_tilt({2, Vec3::UnitZ(), 0.01}), std::invalid_argument);
  EXPECT_TRUE(graph.constraints().empty());
}

TEST(PoseGraph, OdometryConstraintsReproduceTheTrajectory) {
  const test::SquareLoop s = make_square_loop(0);
  const auto constraints = loop::odometry_constraints(s.truth, Mat6::Identity());
  ASSERT_EQ(constraints.size(), s.truth.size() - 1);
  for (const auto& c : constraints) {
    EXPECT_EQ(c.to_index, c.from_index + 1);
    EXPECT_LT(loop::whitened_residual(c, s.truth[c.from_index].T_W_B, s.truth[c.to_index].T_W_B).norm(), 1e-12);
  }
}

}  // namespace
}  // namespace vilslam
