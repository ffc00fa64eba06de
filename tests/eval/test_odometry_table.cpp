// The odometry table's rows: FDE on closed and open routes, ATE, lost runs, the paper's values.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "eval/drift.h"
#include "eval/odometry_table.h"

namespace vilslam::eval {
namespace {

// A closed 10 m x 10 m square walked at 1 m/s, one pose per second (41 poses, 40 m), yaw along the path;
// it ends in its start pose.
Trajectory square() {
  Trajectory traj;
  const Vec3 corners[4] = {{0, 0, 0}, {10, 0, 0}, {10, 10, 0}, {0, 10, 0}};
  for (int i = 0; i <= 40; ++i) {
    const int side = std::min(i / 10, 3);
    const Vec3 dir = (corners[(side + 1) % 4] - corners[side]) / 10.0;
    const Quat q(Eigen::AngleAxisd(std::atan2(dir.y(), dir.x()), Vec3::UnitZ()));
    traj.push_back({s_to_ns(i), i == 40 ? traj.front().T_W_B : SE3(q, corners[side] + dir * (i - 10 * side))});
  }
  return traj;
}

// Adds an offset growing linearly with time to the positions: the last pose is `final` away.
Trajectory drifting(const Trajectory& gt, const Vec3& final) {
  Trajectory est = gt;
  for (std::size_t i = 0; i < est.size(); ++i)
    est[i].T_W_B.translation() += final * (static_cast<double>(i) / static_cast<double>(est.size() - 1));
  return est;
}

TEST(OdometryTable, ClosedRouteFdeIsEndToStartDistanceOverEstimatePath) {
  const Trajectory gt = square();
  const Trajectory est = drifting(gt, Vec3(0.3, 0.4, 0));
  const DriftResult d = evaluate_drift({est, ""}, gt, AlignMode::kPosYaw, true);
  ASSERT_FALSE(d.lost) << d.lost_reason;
  EXPECT_NEAR(d.drift_m, 0.5, 1e-12);
  EXPECT_NEAR(d.path_length_m, path_length_m(est), 1e-12);
  EXPECT_NE(d.path_length_m, 40.0);  // the estimate's own length, not the ground truth's
  EXPECT_NEAR(d.fde_percent, 100 * 0.5 / path_length_m(est), 1e-12);
  EXPECT_GT(d.ate_rmse_m, 0.05);
  EXPECT_LT(d.ate_rmse_m, 0.5);
  EXPECT_EQ(d.poses, 41u);
}

TEST(OdometryTable, OpenRouteFdeIsDriftAgainstGroundTruth) {
  Trajectory gt = square();
  gt.resize(21);  // two sides: ends 14.1 m from its start
  // The estimate lives in another frame (rotated and shifted); start alignment removes that.
  const SE3 T_est_gt(Quat(Eigen::AngleAxisd(0.7, Vec3::UnitZ())), Vec3(5, -3, 1));
  Trajectory est = drifting(gt, Vec3(0, 0.2, 0));
  for (TimedPose& p : est) p.T_W_B = T_est_gt * p.T_W_B;
  const DriftResult d = evaluate_drift({est, ""}, gt, AlignMode::kSe3, false);
  ASSERT_FALSE(d.lost) << d.lost_reason;
  EXPECT_NEAR(d.drift_m, 0.2, 1e-9);
  EXPECT_NEAR(d.path_length_m, 20.0, 1e-9);
  EXPECT_NEAR(d.fde_percent, 1.0, 1e-7);
}

TEST(OdometryTable, ExactEstimateHasNoDrift) {
  const Trajectory gt = square();
  const DriftResult d = evaluate_drift({gt, ""}, gt, AlignMode::kPosYaw, true);
  ASSERT_FALSE(d.lost);
  EXPECT_NEAR(d.fde_percent, 0.0, 1e-12);
  EXPECT_NEAR(d.ate_rmse_m, 0.0, 1e-9);
  EXPECT_NEAR(d.ate_se3_rmse_m, 0.0, 1e-9);
}

// A world tilted by 0.01 rad (a wrong gravity estimate): posyaw keeps the tilt, SE(3) removes it.
TEST(OdometryTable, TiltShowsInPosYawAteOnly) {
  const Trajectory gt = square();
  const SE3 tilt(Quat(Eigen::AngleAxisd(0.01, Vec3::UnitX())), Vec3::Zero());
  Trajectory est = gt;
  for (TimedPose& p : est) p.T_W_B = tilt * p.T_W_B;
  const DriftResult d = evaluate_drift({est, ""}, gt, AlignMode::kPosYaw, true);
  ASSERT_FALSE(d.lost);
  EXPECT_NEAR(d.fde_percent, 0.0, 1e-12);  // a rigid tilt is no drift
  EXPECT_GT(d.ate_rmse_m, 0.02);           // 0.01 rad over +-5 m
  EXPECT_NEAR(d.ate_se3_rmse_m, 0.0, 1e-9);
}

TEST(OdometryTable, LostRuns) {
  const Trajectory gt = square();
  const DriftResult threw = evaluate_drift({{}, "mapper diverged"}, gt, AlignMode::kPosYaw, true);
  EXPECT_TRUE(threw.lost);
  EXPECT_NE(threw.lost_reason.find("mapper diverged"), std::string::npos);

  EXPECT_TRUE(evaluate_drift({Trajectory(gt.begin(), gt.begin() + 1), ""}, gt, AlignMode::kPosYaw, true).lost);

  Trajectory nan = gt;
  nan[7].T_W_B.translation().x() = std::numeric_limits<double>::quiet_NaN();
  const DriftResult not_finite = evaluate_drift({nan, ""}, gt, AlignMode::kPosYaw, true);
  EXPECT_TRUE(not_finite.lost);
  EXPECT_NE(not_finite.lost_reason.find("finite"), std::string::npos);

  // The first 12 of 40 s: 30 % coverage, below the 50 % needed.
  const DriftResult short_run = evaluate_drift({Trajectory(gt.begin(), gt.begin() + 13), ""}, gt, AlignMode::kPosYaw, true);
  EXPECT_TRUE(short_run.lost);
  EXPECT_NE(short_run.lost_reason.find("covers 30 %"), std::string::npos) << short_run.lost_reason;

  // Drifting 12 m over a 40 m route strays more than 10 % (4 m) from the ground truth even after alignment.
  const DriftResult diverged = evaluate_drift({drifting(gt, Vec3(12, 0, 0)), ""}, gt, AlignMode::kPosYaw, true);
  EXPECT_TRUE(diverged.lost);
  EXPECT_NE(diverged.lost_reason.find("strays"), std::string::npos) << diverged.lost_reason;
  EXPECT_NEAR(diverged.drift_m, 12.0, 1e-9);  // the numbers are still reported
  // 1 m over 40 m stays within it.
  EXPECT_FALSE(evaluate_drift({drifting(gt, Vec3(1, 0, 0)), ""}, gt, AlignMode::kPosYaw, true).lost);
}

TEST(OdometryTable, RowUsesTheRouteGapAndPassesCounts) {
  OdometryInputs in;
  in.preset = "tunnel";
  in.source = "simulated, seed 1";
  in.gt_T_W_I = square();
  const SE3 T_I_L(Quat::Identity(), Vec3(0.05, 0, 0.2));
  for (const TimedPose& p : in.gt_T_W_I) in.gt_T_W_L.push_back({p.t_ns, p.T_W_B * T_I_L});
  in.vio = {drifting(in.gt_T_W_I, Vec3(0.4, 0, 0)), ""};
  in.vil = {drifting(in.gt_T_W_L, Vec3(0, 0.1, 0)), ""};
  // LiDAR-only in its first sweep's frame: SE(3) alignment and the end-start FDE ignore the frame.
  const SE3 T_L0_W = in.gt_T_W_L.front().T_W_B.inverse();
  Trajectory lidar_only = drifting(in.gt_T_W_L, Vec3(2, 0, 0));
  for (TimedPose& p : lidar_only) p.T_W_B = T_L0_W * p.T_W_B;
  in.lidar_only = {lidar_only, ""};
  in.vil_degenerate = 3;
  in.vil_sweeps = 40;
  in.lidar_only_degenerate = 17;
  in.lidar_only_sweeps = 41;
  const OdometryRow row = compute_odometry_row(in);
  EXPECT_TRUE(row.closed);
  EXPECT_NEAR(row.gt_gap_m, 0.0, 1e-12);
  EXPECT_NEAR(row.gt_length_m, 40.0, 1e-12);
  EXPECT_NEAR(row.vio.drift_m, 0.4, 1e-12);
  EXPECT_NEAR(row.vil.drift_m, 0.1, 1e-12);
  EXPECT_NEAR(row.lidar_only.drift_m, 2.0, 1e-9);
  EXPECT_EQ(row.vio.align, AlignMode::kPosYaw);
  EXPECT_EQ(row.vil.align, AlignMode::kPosYaw);
  EXPECT_EQ(row.lidar_only.align, AlignMode::kSe3);
  EXPECT_LT(row.lidar_only.ate_rmse_m, 1.0);  // aligned despite the other frame
  EXPECT_EQ(row.lidar_only.ate_se3_rmse_m, row.lidar_only.ate_rmse_m);
  EXPECT_EQ(row.vil_degenerate, 3u);
  EXPECT_EQ(row.lidar_only_degenerate, 17u);
  EXPECT_EQ(row.lidar_only_sweeps, 41u);

  in.gt_T_W_I.pop_back();  // now ends 1 m short of its start: open route
  in.gt_T_W_L.pop_back();
  const OdometryRow open = compute_odometry_row(in);
  EXPECT_FALSE(open.closed);
  EXPECT_NEAR(open.gt_gap_m, 1.0, 1e-12);

  in.gt_T_W_I.resize(1);
  EXPECT_THROW(compute_odometry_row(in), std::invalid_argument);
}

// The true relative pose T_from_to of two instants of a trajectory, perturbed by `error` (right-multiplied).
LoopToEvaluate loop_between(const Trajectory& gt, int from_s, int to_s, const SE3& error, const SE3& epnp_error) {
  const SE3 T_true = pose_at(gt, s_to_ns(from_s)).inverse() * pose_at(gt, s_to_ns(to_s));
  return {s_to_ns(from_s), s_to_ns(to_s), T_true * error, T_true * epnp_error};
}

TEST(OdometryTable, LoopClosedTrajectoryAndLoopsInTheLidarFrame) {
  OdometryInputs in;
  in.preset = "hallway";
  in.gt_T_W_I = square();
  // A rotated LiDAR: relative poses in the IMU frame differ from those in the LiDAR frame.
  const SE3 T_I_L(Quat(Eigen::AngleAxisd(0.4, Vec3::UnitZ()) * Eigen::AngleAxisd(0.2, Vec3::UnitX())), Vec3(0.3, 0, 0.5));
  for (const TimedPose& p : in.gt_T_W_I) in.gt_T_W_L.push_back({p.t_ns, p.T_W_B * T_I_L});
  in.vio = {in.gt_T_W_I, ""};
  in.vil = {drifting(in.gt_T_W_L, Vec3(0.8, 0, 0)), ""};
  in.lidar_only = {in.gt_T_W_L, ""};
  in.vil_final = {drifting(in.gt_T_W_L, Vec3(0, 0.05, 0)), ""};
  const SE3 one_degree(Quat(Eigen::AngleAxisd(M_PI / 180, Vec3::UnitY())), Vec3::Zero());
  LoopClosureInputs loops;
  loops.candidates_examined = 7;
  // A true loop (0.1 m and 1 degree off; EPnP 0.2 m off) and a false one (0.5 m off; EPnP 0.6 m off).
  loops.accepted.push_back(loop_between(in.gt_T_W_L, 3, 37, SE3(one_degree.quat(), Vec3(0, 0.1, 0)),
                                        SE3(Quat::Identity(), Vec3(0.2, 0, 0))));
  loops.accepted.push_back(loop_between(in.gt_T_W_L, 5, 39, SE3(Quat::Identity(), Vec3(0, 0, 0.5)),
                                        SE3(Quat::Identity(), Vec3(0, 0.6, 0))));
  in.loops = loops;
  const OdometryRow row = compute_odometry_row(in);

  EXPECT_NEAR(row.vil.drift_m, 0.8, 1e-12);  // odometry keeps its drift
  ASSERT_FALSE(row.vil_final.lost) << row.vil_final.lost_reason;
  EXPECT_EQ(row.vil_final.align, AlignMode::kPosYaw);  // the same rules as VIL
  EXPECT_NEAR(row.vil_final.drift_m, 0.05, 1e-12);
  EXPECT_NEAR(row.vil_final.fde_percent, 100 * 0.05 / path_length_m(in.vil_final.poses), 1e-12);
  EXPECT_GT(row.vil_final.ate_se3_rmse_m, 0.0);
  EXPECT_LT(row.vil_final.ate_se3_rmse_m, row.vil.ate_se3_rmse_m);

  ASSERT_TRUE(row.loops.has_value());
  EXPECT_EQ(row.loops->candidates_examined, 7u);
  const LoopEvaluation& e = row.loops->accepted;
  ASSERT_EQ(e.loops.size(), 2u);
  EXPECT_EQ(e.true_loops, 1);
  EXPECT_EQ(e.false_loops, 1);
  EXPECT_FALSE(e.loops[0].is_false);
  EXPECT_TRUE(e.loops[1].is_false);
  EXPECT_NEAR(e.loops[0].translation_m, 0.1, 1e-9);
  EXPECT_NEAR(e.loops[0].rotation_deg, 1.0, 1e-9);
  EXPECT_NEAR(e.median_translation_m, 0.3, 1e-9);     // of 0.1 and 0.5
  EXPECT_NEAR(e.median_rotation_deg, 0.5, 1e-9);      // of 1 and 0
  EXPECT_NEAR(e.median_epnp_translation_m, 0.4, 1e-9);  // of 0.2 and 0.6
  EXPECT_NEAR(e.median_epnp_rotation_deg, 0.0, 1e-9);

  // A failed VIL run: no loop closure result, the loop-closed trajectory is lost with the run's message.
  in.loops.reset();
  in.vil_final = {{}, "vocabulary missing"};
  const OdometryRow failed = compute_odometry_row(in);
  EXPECT_FALSE(failed.loops.has_value());
  EXPECT_TRUE(failed.vil_final.lost);
  EXPECT_NE(failed.vil_final.lost_reason.find("vocabulary missing"), std::string::npos);

  // A loop instant outside the ground truth cannot be evaluated.
  loops.accepted.push_back({s_to_ns(2), s_to_ns(41), SE3(), std::nullopt});
  in.loops = loops;
  EXPECT_THROW(compute_odometry_row(in), std::invalid_argument);
}

TEST(OdometryTable, PaperValues) {
  EXPECT_DOUBLE_EQ(paper_odometry("highbay")->vil_slam_fde_percent, 0.08);
  EXPECT_DOUBLE_EQ(*paper_odometry("highbay")->loam_fde_percent, 0.56);
  EXPECT_DOUBLE_EQ(paper_odometry("hallway")->vil_slam_fde_percent, 0.61);
  EXPECT_DOUBLE_EQ(*paper_odometry("hallway")->loam_fde_percent, 0.91);
  EXPECT_DOUBLE_EQ(paper_odometry("tunnel")->vil_slam_fde_percent, 1.86);
  EXPECT_FALSE(paper_odometry("tunnel")->loam_fde_percent.has_value());
  EXPECT_DOUBLE_EQ(paper_odometry("tunnel")->length_m, 85);
  EXPECT_FALSE(paper_odometry("room").has_value());
  // After loop closure: the text of the paper's results section.
  EXPECT_DOUBLE_EQ(*paper_odometry("hallway")->vil_slam_loop_fde_percent, 0.05);
  EXPECT_DOUBLE_EQ(*paper_odometry("tunnel")->vil_slam_loop_fde_percent, 0.08);
  EXPECT_FALSE(paper_odometry("highbay")->vil_slam_loop_fde_percent.has_value());
  EXPECT_NE(paper_odometry("highbay")->loop_remark.find("closes the loop"), std::string::npos);
  EXPECT_FALSE(paper_odometry("loop")->vil_slam_loop_fde_percent.has_value());
  EXPECT_NE(paper_odometry("loop")->loop_remark.find("no loop"), std::string::npos);
  EXPECT_TRUE(paper_odometry("outdoor")->loop_remark.empty());
  // MRE (m): VIL-SLAM and LOAM; "x" (none) for the tunnel and the outdoor test.
  EXPECT_DOUBLE_EQ(*paper_odometry("highbay")->vil_slam_mre_m, 0.08);
  EXPECT_DOUBLE_EQ(*paper_odometry("highbay")->loam_mre_m, 0.22);
  EXPECT_DOUBLE_EQ(*paper_odometry("hallway")->vil_slam_mre_m, 0.10);
  EXPECT_DOUBLE_EQ(*paper_odometry("hallway")->loam_mre_m, 0.27);
  EXPECT_DOUBLE_EQ(*paper_odometry("loop")->vil_slam_mre_m, 0.22);
  EXPECT_DOUBLE_EQ(*paper_odometry("loop")->loam_mre_m, 0.36);
  EXPECT_FALSE(paper_odometry("tunnel")->vil_slam_mre_m.has_value());
  EXPECT_FALSE(paper_odometry("outdoor")->loam_mre_m.has_value());
}

}  // namespace
}  // namespace vilslam::eval
