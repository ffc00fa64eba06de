// eval-loops: each constraint's error against the true relative pose, the false-loop rule, the EPnP medians,
// and the CLI on a dataset-free ground truth file.
#include <gtest/gtest.h>

#include <fstream>

#include "eval/loop_eval.h"
#include "io/trajectory_io.h"
#include "test_util.h"

namespace vilslam::eval {
namespace {

// A curved ground truth, 100 poses at 0.1 s.
Trajectory truth() {
  Trajectory gt;
  for (int k = 0; k < 100; ++k) {
    const double a = 0.05 * k;
    gt.push_back({TimeNs(k) * 100'000'000, SE3(Quat(Eigen::AngleAxisd(a, Vec3::UnitZ())),
                                               Vec3(10 * std::sin(a), 10 * (1 - std::cos(a)), 0.01 * k))});
  }
  return gt;
}

SE3 true_relative(const Trajectory& gt, int u, int v) { return gt[u].T_W_B.inverse() * gt[v].T_W_B; }

TEST(LoopEval, ErrorsAreThoseOfThePerturbation) {
  const Trajectory gt = truth();
  const SE3 small(Quat(Eigen::AngleAxisd(0.5 * M_PI / 180, Vec3::UnitX())), Vec3(0.03, 0.0, 0.04));
  const SE3 large(Quat::Identity(), Vec3(0.0, 0.31, 0.0));
  const SE3 turned(Quat(Eigen::AngleAxisd(3.1 * M_PI / 180, Vec3::UnitY())), Vec3::Zero());
  std::vector<LoopToEvaluate> loops = {
      {gt[5].t_ns, gt[80].t_ns, true_relative(gt, 5, 80) * small, true_relative(gt, 5, 80) * large},
      {gt[10].t_ns, gt[90].t_ns, true_relative(gt, 10, 90) * large, std::nullopt},
      {gt[20].t_ns, gt[95].t_ns, true_relative(gt, 20, 95) * turned, true_relative(gt, 20, 95) * small}};
  const LoopEvaluation e = evaluate_loops(loops, gt);
  ASSERT_EQ(e.loops.size(), 3u);
  EXPECT_NEAR(e.loops[0].translation_m, 0.05, 1e-9);
  EXPECT_NEAR(e.loops[0].rotation_deg, 0.5, 1e-9);
  EXPECT_FALSE(e.loops[0].is_false);
  EXPECT_NEAR(*e.loops[0].epnp_translation_m, 0.31, 1e-9);
  EXPECT_TRUE(e.loops[1].is_false);  // 0.31 m > 0.3 m
  EXPECT_FALSE(e.loops[1].epnp_translation_m.has_value());
  EXPECT_TRUE(e.loops[2].is_false);  // 3.1 deg > 3 deg
  EXPECT_EQ(e.true_loops, 1);
  EXPECT_EQ(e.false_loops, 2);
  EXPECT_NEAR(e.median_translation_m, 0.05, 1e-9);             // of 0.05, 0.31, 0
  EXPECT_NEAR(e.median_epnp_translation_m, (0.31 + 0.05) / 2, 1e-9);  // of the two EPnP estimates
}

TEST(LoopEval, InstantsBetweenSamplesAreInterpolatedAndOutsideRejected) {
  const Trajectory gt = truth();
  const TimeNs mid_ns = (gt[40].t_ns + gt[41].t_ns) / 2;
  const SE3 T_true = gt[3].T_W_B.inverse() * pose_at(gt, mid_ns);
  EXPECT_LT(evaluate_loops({{gt[3].t_ns, mid_ns, T_true, std::nullopt}}, gt).loops[0].translation_m, 1e-12);
  EXPECT_THROW(evaluate_loops({{gt[3].t_ns, gt.back().t_ns + 1, T_true, std::nullopt}}, gt), std::invalid_argument);
}

TEST(CmdEvalLoops, CountsFalseLoopsAndRejectsBadInput) {
  const Trajectory gt = truth();
  const auto dir = test::temp_dir();
  write_trajectory((dir / "gt.tum").string(), gt, TrajectoryFormat::kTum);
  const auto row = [&](int u, int v, const SE3& error) {
    const SE3 T = true_relative(gt, u, v) * error;
    char buf[512];
    std::snprintf(buf, sizeof buf, "%lld,%lld,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g\n",
                  static_cast<long long>(gt[u].t_ns), static_cast<long long>(gt[v].t_ns), T.translation().x(),
                  T.translation().y(), T.translation().z(), T.quat().x(), T.quat().y(), T.quat().z(), T.quat().w());
    return std::string(buf);
  };
  std::ofstream(dir / "loops.csv") << row(2, 70, SE3(Quat::Identity(), Vec3(0.01, 0, 0)))
                                   << row(4, 75, SE3(Quat::Identity(), Vec3(0.5, 0, 0)));
  const test::CliResult ok = test::run_cli("eval-loops --loops " + (dir / "loops.csv").string() + " --gt " +
                                           (dir / "gt.tum").string() + " --json " + (dir / "e.json").string());
  ASSERT_EQ(ok.exit_code, 0) << ok.output;
  EXPECT_NE(ok.output.find("loops 2: true 1, false 1"), std::string::npos) << ok.output;
  EXPECT_NE(test::read_file_bytes(dir / "e.json").find("\"false_loops\": 1"), std::string::npos);
  std::ofstream(dir / "late.csv") << "200000000,20000000000,0,0,0,0,0,0,1\n";  // ends after the ground truth
  const test::CliResult late = test::run_cli("eval-loops --loops " + (dir / "late.csv").string() + " --gt " +
                                             (dir / "gt.tum").string());
  EXPECT_EQ(late.exit_code, 2) << late.output;
  EXPECT_NE(late.output.find("late.csv"), std::string::npos) << late.output;
  const test::CliResult missing = test::run_cli("eval-loops --loops " + (dir / "none.csv").string() + " --gt " +
                                                (dir / "gt.tum").string());
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_NE(missing.output.find("none.csv"), std::string::npos) << missing.output;
}

}  // namespace
}  // namespace vilslam::eval
