// Loop closure inside `vilslam run --mode vil` on a short closed route (the room preset, 8 m, one lap): the
// return to the start is detected and every accepted loop is true against ground truth, the outputs are
// consistent with each other, bit-identical over two runs and with the modules on one thread, and `loop_closure.enabled: false` turns it off.
// The same lap with its camera stamps delayed shows the camera-IMU time offset estimation.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "eval/loop_eval.h"
#include "io/dataset_groundtruth.h"
#include "io/trajectory_io.h"
#include "loop/loop_constraints_io.h"
#include "pipeline/time_offset_pass.h"
#include "report/run_dir.h"
#include "sim/calibration_errors.h"
#include "delayed_camera_reader.h"
#include "shared_simulation.h"
#include "test_util.h"

namespace vilslam {
namespace {

namespace fs = std::filesystem;

// The lap lasts about 10 s: candidates must be at least 4 s old instead of the default 30 s.
constexpr const char* kShortGapConfig = "loop_closure:\n  min_time_gap_s: 4.0\n";

class LoopClosureRun : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    const fs::path dir = test::process_temp_root() / "room8";
    fs::remove_all(dir);
    fs::create_directories(dir);
    data_ = new fs::path(test::shared_simulation("room --length 8 --seed 2"));
    ASSERT_FALSE(data_->empty());
    std::ofstream(dir / "short_gap.yaml") << kShortGapConfig;
    std::ofstream(dir / "off.yaml") << kShortGapConfig << "  enabled: false\n";
    std::ofstream(dir / "one_thread.yaml") << kShortGapConfig << "pipeline:\n  threads: false\n";
    for (const char* run : {"a", "b"}) {
      const test::CliResult r = test::run_cli("run --mode vil " + data_->string() + " --config " +
                                              (dir / "short_gap.yaml").string() + " --out " + (dir / run).string());
      ASSERT_EQ(r.exit_code, 0) << r.output;
      if (std::string(run) == "a") output_a_ = new std::string(r.output);
    }
    const test::CliResult serial = test::run_cli("run --mode vil " + data_->string() + " --config " +
                                                 (dir / "one_thread.yaml").string() + " --out " + (dir / "serial").string());
    ASSERT_EQ(serial.exit_code, 0) << serial.output;
    const test::CliResult off = test::run_cli("run --mode vil " + data_->string() + " --config " +
                                              (dir / "off.yaml").string() + " --out " + (dir / "off").string());
    ASSERT_EQ(off.exit_code, 0) << off.output;
    runs_ = new fs::path(dir);
  }
  static void TearDownTestSuite() {
    delete data_;
    delete runs_;
    delete output_a_;
  }
  static Trajectory read(const std::string& run, const std::string& file) {
    return read_trajectory((*runs_ / run / file).string(), TrajectoryFormat::kTum);
  }
  // The events of one timings.json series; -1 when the run has no such series.
  static double timed_events(const std::string& run, const std::string& series) {
    for (const report::TimingSummaryRow& row : report::read_run_dir((*runs_ / run).string()).timings.summaries) {
      if (row.series == series) return row.frames;
    }
    return -1.0;
  }
  static fs::path* data_;
  static fs::path* runs_;
  static std::string* output_a_;
};
fs::path* LoopClosureRun::data_ = nullptr;
fs::path* LoopClosureRun::runs_ = nullptr;
std::string* LoopClosureRun::output_a_ = nullptr;

TEST_F(LoopClosureRun, EstimatesAnUnknownCameraDelayWithinOneMillisecond) {
  // The simulated camera's own clock offset (sensor realism, docs/simulator.md) comes on top of the delay.
  const double own_delay_s = sim::CalibrationErrors{}.camera_time_offset_s;
  for (const TimeNs delay_ns : {5'000'000, -8'000'000}) {
    test::DelayedCameraReader reader(open_dataset(data_->string()), delay_ns);
    const auto estimate = estimate_sequence_time_offset(reader, FrontendConfig{}, TimeOffsetConfig{});
    ASSERT_TRUE(estimate) << delay_ns;
    EXPECT_NEAR(estimate->offset_s, -(ns_to_s(delay_ns) + own_delay_s), 0.001) << delay_ns;
    EXPECT_LT(estimate->rms_rad, estimate->rms_zero_offset_rad) << delay_ns;
  }
}

TEST_F(LoopClosureRun, DetectsTheReturnWithTrueConstraints) {
  const std::vector<loop::LoopRow> rows = loop::read_loop_rows((*runs_ / "a" / "loops.csv").string());
  ASSERT_GE(rows.size(), 1u) << test::read_file_bytes(*runs_ / "a" / "loop_candidates.csv");
  std::vector<eval::LoopToEvaluate> loops;
  for (const loop::LoopRow& r : rows) {
    loops.push_back({r.from_t_ns, r.to_t_ns, r.T_from_to, r.T_from_to_epnp});
    EXPECT_GE(r.to_t_ns - r.from_t_ns, 4'000'000'000) << "candidate younger than the time gap";
  }
  const eval::LoopEvaluation e = eval::evaluate_loops(loops, dataset_groundtruth(data_->string(), GroundTruthFrame::kLidar));
  EXPECT_EQ(e.false_loops, 0);
  // The bound is on the median (docs/loop.md); single loops get more room: the weakest one here (3.4 s ->
  // 8.8 s, while the robot accelerates) is 3.3 cm off in the gcc build and 6.1 cm in clang's, the same code
  // landing a little differently (docs/fuzzing.md).
  EXPECT_LT(e.median_translation_m, 0.03);
  EXPECT_LT(e.median_rotation_deg, 0.2);
  for (const eval::LoopError& l : e.loops) {
    EXPECT_LT(l.translation_m, 0.10);
    EXPECT_LT(l.rotation_deg, 2.0);
  }
}

TEST_F(LoopClosureRun, OutputsAgree) {
  const Trajectory odometry = read("a", "lidar.tum");
  const Trajectory global = read("a", "lidar_global.tum");
  const Trajectory final_poses = read("a", "lidar_final.tum");
  ASSERT_EQ(global.size(), odometry.size());
  ASSERT_EQ(final_poses.size(), odometry.size());
  // Until the first loop the published poses are the odometry; the final graph differs from both after it.
  const TimeNs first_loop_ns = loop::read_loop_rows((*runs_ / "a" / "loops.csv").string()).at(0).to_t_ns;
  double final_moved_m = 0;
  for (std::size_t i = 0; i < odometry.size(); ++i) {
    EXPECT_EQ(global[i].t_ns, odometry[i].t_ns);
    if (odometry[i].t_ns <= first_loop_ns) {
      EXPECT_LT((global[i].T_W_B.translation() - odometry[i].T_W_B.translation()).norm(), 1e-9) << i;
    }
    final_moved_m = std::max(final_moved_m, (final_poses[i].T_W_B.translation() - odometry[i].T_W_B.translation()).norm());
  }
  EXPECT_GT(final_moved_m, 1e-4);
  // Every examined candidate names its stage; the accepted ones are the loops.
  const std::string candidates = test::read_file_bytes(*runs_ / "a" / "loop_candidates.csv");
  std::size_t accepted = 0;
  for (std::size_t at = candidates.find(",accepted\n"); at != std::string::npos; at = candidates.find(",accepted\n", at + 1))
    ++accepted;
  EXPECT_EQ(accepted, loop::read_loop_rows((*runs_ / "a" / "loops.csv").string()).size());
  const std::string timings = test::read_file_bytes(*runs_ / "a" / "timings.json");
  EXPECT_NE(timings.find("\"loops_accepted\": " + std::to_string(accepted)), std::string::npos) << timings;
  // Rejected as untrusted: the candidates whose images matched and whose geometry failed a check.
  std::size_t untrusted = 0;
  for (const char* stage : {",icp_fitness\n", ",icp_degenerate\n", ",epnp_icp_disagree\n", ",odometry_disagree\n"}) {
    for (std::size_t at = candidates.find(stage); at != std::string::npos; at = candidates.find(stage, at + 1)) ++untrusted;
  }
  EXPECT_NE(timings.find("\"loops_rejected\": " + std::to_string(untrusted)), std::string::npos) << timings;
  EXPECT_NE(output_a_->find("rejected as untrusted " + std::to_string(untrusted) + " "), std::string::npos) << *output_a_;
  // The final solve with the tilt factors (tilt_final_only, the default) is timed once, after the loops.
  EXPECT_EQ(timed_events("a", "loop_final_solve"), 1.0);
  EXPECT_NE(output_a_->find("final solve with the tilt factors ms: "), std::string::npos) << *output_a_;
  EXPECT_EQ(timed_events("a", "loop_correction"), static_cast<double>(accepted));
}

// Two threaded runs, and a run with every module on one thread: the same bytes.
TEST_F(LoopClosureRun, RunsAreBitIdenticalThreadedOrNot) {
  for (const char* file : {"lidar.tum", "lidar_global.tum", "lidar_final.tum", "loops.csv", "loop_candidates.csv",
                           "vio_camera.tum", "vio_imu.tum", "degeneracy.csv", "vio_status.csv", "lidar_status.csv"}) {
    EXPECT_EQ(test::read_file_bytes(*runs_ / "a" / file), test::read_file_bytes(*runs_ / "b" / file)) << file;
    EXPECT_EQ(test::read_file_bytes(*runs_ / "a" / file), test::read_file_bytes(*runs_ / "serial" / file)) << file;
  }
}

TEST_F(LoopClosureRun, DisabledGivesTheOdometryOnly) {
  EXPECT_EQ(loop::read_loop_rows((*runs_ / "off" / "loops.csv").string()).size(), 0u);
  EXPECT_EQ(test::read_file_bytes(*runs_ / "off" / "lidar_final.tum"), test::read_file_bytes(*runs_ / "off" / "lidar.tum"));
  EXPECT_EQ(test::read_file_bytes(*runs_ / "off" / "lidar_global.tum"),
            test::read_file_bytes(*runs_ / "off" / "lidar.tum"));
  EXPECT_EQ(timed_events("off", "loop_final_solve"), 0.0);
  // Up to the first loop the enabled run maps exactly like the disabled one.
  EXPECT_EQ(read("off", "lidar.tum").front().T_W_B.translation(), read("a", "lidar.tum").front().T_W_B.translation());
}

}  // namespace
}  // namespace vilslam
