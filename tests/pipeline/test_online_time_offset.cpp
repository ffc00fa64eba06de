// The camera-IMU time offset estimated as the run goes (`time_offset.online`, pipeline/online_time_offset.h) on
// the simulated 8 m room lap with ideal sensors, its camera stamps delayed by an amount the calibration does not
// know: the estimates converge to the delay, and the frames after each estimate are moved by it, which takes back
// part of the error the delay made (the first estimate needs 50 intervals of the 11 s lap, about 5 s).
#include <gtest/gtest.h>

#include <filesystem>

#include "delayed_camera_reader.h"
#include "eval/trajectory_eval.h"
#include "io/dataset_groundtruth.h"
#include "pipeline/offline_runner.h"
#include "test_util.h"

namespace vilslam {
namespace {

namespace fs = std::filesystem;

class OnlineTimeOffsetRun : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    const fs::path dir = test::process_temp_root() / "room8_ideal";
    fs::remove_all(dir);
    data_ = new fs::path(dir / "data");
    const test::CliResult sim =
        test::run_cli("simulate room --length 8 --seed 2 --ideal-sensors --out " + data_->string());
    ASSERT_EQ(sim.exit_code, 0) << sim.output;
  }
  static void TearDownTestSuite() { delete data_; }

  // The lap lasts about 11 s: an estimate every 2 s instead of 5.
  static OfflineRunResult run(TimeNs delay_ns, bool online) {
    test::DelayedCameraReader reader(open_dataset(data_->string()), delay_ns);
    OfflineRunConfig config;
    config.mode = RunMode::kVio;
    config.time_offset.online = online;
    config.time_offset.update_every_s = 2.0;
    return run_offline(reader, config);
  }
  static double ate_m(const OfflineRunResult& r) {
    eval::TrajectoryEvalConfig config;
    config.align = eval::AlignMode::kPosYaw;
    const Trajectory gt = dataset_groundtruth(data_->string(), GroundTruthFrame::kImu);
    return eval::evaluate_trajectory(r.camera_states, gt, config).ape.trans.rmse;
  }
  static fs::path* data_;
};
fs::path* OnlineTimeOffsetRun::data_ = nullptr;

TEST_F(OnlineTimeOffsetRun, ConvergesToAnUnknownCameraDelayWithinOneMillisecond) {
  for (const TimeNs delay_ns : {5'000'000, -8'000'000}) {
    const OfflineRunResult r = run(delay_ns, true);
    ASSERT_GE(r.time_offset_online.size(), 3u) << delay_ns;
    for (const OnlineTimeOffsetUpdate& u : r.time_offset_online) {
      std::printf("delay %.0f ms: at %.1f s estimated %.2f ms from %d intervals, applied %.2f ms\n",
                  1e-6 * static_cast<double>(delay_ns), ns_to_s(u.t_ns), 1e3 * u.estimate.offset_s,
                  u.estimate.intervals, 1e3 * u.applied_offset_s);
    }
    const OnlineTimeOffsetUpdate& last = r.time_offset_online.back();
    EXPECT_NEAR(last.estimate.offset_s, -ns_to_s(delay_ns), 0.001) << delay_ns;
    EXPECT_NEAR(last.applied_offset_s, -ns_to_s(delay_ns), 0.001) << delay_ns;
    EXPECT_LT(last.estimate.rms_rad, last.estimate.rms_zero_offset_rad) << delay_ns;
  }
}

TEST_F(OnlineTimeOffsetRun, MovingTheFramesByTheEstimateTakesBackPartOfTheDelaysError) {
  const double no_delay_m = ate_m(run(0, false));
  const double ignored_m = ate_m(run(8'000'000, false));
  const double estimated_m = ate_m(run(8'000'000, true));
  std::printf("VIO ATE (posyaw): no delay %.4f m; 8 ms delay ignored %.4f m, estimated online %.4f m\n", no_delay_m,
              ignored_m, estimated_m);
  EXPECT_LT(estimated_m, 0.8 * ignored_m);
  EXPECT_GT(ignored_m, 1.5 * no_delay_m);  // the delay matters on this lap
}

}  // namespace
}  // namespace vilslam
