// Sensor faults inside one run (docs/pipeline.md, "Sensor faults"): the simulated 8 m room lap with a 2 s camera
// blackout, a 0.5 s IMU gap and a 1.5 s LiDAR dropout. The run finishes, each module's status file says what
// happened when it happened, and the LiDAR poses stay on the truth; with the IMU factor across the gap taken at
// face value (no ImuGapModel noise) and the loss check off, the VIO goes far off; with the loss check on, the VIO
// declares itself lost, starts again, and the LiDAR poses stay on the truth.
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "common/time.h"
#include "status_csv.h"
#include "test_util.h"

namespace vilslam {
namespace {

namespace fs = std::filesystem;

constexpr double kSequenceStartS = 1.0;  // the simulator's first stamp (start_time_ns)
// The stereo calibration is exact here: with the simulator's default stereo errors (cam1 0.1 deg and the lenses up
// to 0.5 px off the written calibration, 2026-12-08) the face-value gap is found lost only at 8.05 s, and the
// restarted VIO ends 0.75 m off against the face value's 0.70 m (issue 61: the loss check's thresholds were set on
// an exact stereo calibration, and the robustness suite is to decide them again).
constexpr const char* kFaults =
    "faults:\n  camera_blackouts: [[3.0, 5.0]]\n  imu_gaps: [[6.0, 6.5]]\n  lidar_dropouts: [[7.0, 8.5]]\n"
    "calibration_errors:\n  stereo_rotation_deg: 0\n  intrinsics_px: 0\n";
constexpr const char* kShortGap = "loop_closure:\n  min_time_gap_s: 4.0\n";  // a lap lasts about 10 s

struct CsvRow {
  double t_s = 0;  // since the sequence start
  std::vector<std::string> cells;
};

std::vector<CsvRow> read_status_csv(const fs::path& file) {
  std::vector<CsvRow> rows;
  for (test::StatusRow& r : test::read_status_rows(file)) rows.push_back({ns_to_s(r.t_ns) - kSequenceStartS, std::move(r.cells)});
  return rows;
}

class SensorFaults : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    root_ = new fs::path(test::process_temp_root() / "sensor_faults");
    fs::remove_all(*root_);
    fs::create_directories(*root_);
    std::ofstream(*root_ / "faults.yaml") << kFaults;
    std::ofstream(*root_ / "run.yaml") << kShortGap;
    const std::string face_value = std::string(kShortGap) + "vio:\n  imu_gap:\n    rate_sigma_rad_s: 0\n    accel_sigma_m_s2: 0\n";
    std::ofstream(*root_ / "restarted.yaml") << face_value;
    std::ofstream(*root_ / "face_value.yaml") << face_value << "  loss:\n    enabled: false\n";
    const test::CliResult sim = test::run_cli("simulate room --length 8 --seed 2 --config " +
                                              (*root_ / "faults.yaml").string() + " --out " + data());
    ASSERT_EQ(sim.exit_code, 0) << sim.output;
    output_ = new test::CliResult(test::run_cli("run --mode vil " + data() + " --config " +
                                                (*root_ / "run.yaml").string() + " --out " + run("run")));
    ASSERT_EQ(output_->exit_code, 0) << output_->output;
    const test::CliResult face = test::run_cli("run --mode vil " + data() + " --config " +
                                               (*root_ / "face_value.yaml").string() + " --out " + run("face_value"));
    ASSERT_EQ(face.exit_code, 0) << face.output;
    restarted_ = new test::CliResult(test::run_cli("run --mode vil " + data() + " --config " +
                                                   (*root_ / "restarted.yaml").string() + " --out " + run("restarted")));
    ASSERT_EQ(restarted_->exit_code, 0) << restarted_->output;
  }
  static void TearDownTestSuite() {
    delete root_;
    delete output_;
    delete restarted_;
  }
  static std::string data() { return (*root_ / "data").string(); }
  static std::string run(const std::string& name) { return (*root_ / name).string(); }
  // SE(3)-aligned APE RMSE (m) of a run's trajectory against the true poses of its frame.
  static double ape_m(const std::string& run_name, const std::string& file, const std::string& frame) {
    const fs::path json = *root_ / (run_name + "_" + file + ".json");
    const test::CliResult e = test::run_cli("eval --est " + run(run_name) + "/" + file + " --gt " + data() +
                                            " --gt-frame " + frame + " --align se3 --json " + json.string());
    EXPECT_EQ(e.exit_code, 0) << e.output;
    return YAML::LoadFile(json.string())["ape"]["rmse"].as<double>();
  }

  static fs::path* root_;
  static test::CliResult* output_;
  static test::CliResult* restarted_;  // the gap at face value, the VIO's loss check on (the default)
};
fs::path* SensorFaults::root_ = nullptr;
test::CliResult* SensorFaults::output_ = nullptr;
test::CliResult* SensorFaults::restarted_ = nullptr;

TEST_F(SensorFaults, EachModulesStatusSaysWhatHappenedAndWhen) {
  ASSERT_NE(output_, nullptr);
  // VIO: every state inside the blackout saw nothing; the states whose IMU interval crossed the gap say so,
  // with the gap's length summed; nothing of either elsewhere.
  int blind = 0, gap_states = 0;
  double gap_s = 0;
  for (const CsvRow& r : read_status_csv(run("run") + "/vio_status.csv")) {
    const std::string& status = r.cells.at(1);
    if (r.t_s >= 3.0 && r.t_s < 5.0) {
      EXPECT_EQ(status, "inertial_only") << r.t_s;
      ++blind;
    } else {
      EXPECT_NE(status, "inertial_only") << r.t_s;
    }
    if (status == "imu_gap") {
      EXPECT_GE(r.t_s, 6.0);
      EXPECT_LE(r.t_s, 6.55);
      ++gap_states;
      gap_s += std::stod(r.cells.at(4));
    }
  }
  EXPECT_EQ(blind, 40);  // 20 Hz
  EXPECT_GE(gap_states, 10);
  EXPECT_NEAR(gap_s, 0.5, 0.02);
  // LiDAR: one sweep after 1.5 s without sweeps, the first after the dropout.
  std::vector<CsvRow> after_gap;
  for (const CsvRow& r : read_status_csv(run("run") + "/lidar_status.csv")) {
    if (r.cells.at(1) == "after_gap") after_gap.push_back(r);
  }
  ASSERT_EQ(after_gap.size(), 1u);
  EXPECT_NEAR(std::stod(after_gap[0].cells.at(2)), 1.5, 0.11);
  EXPECT_GT(after_gap[0].t_s, 8.5);
  EXPECT_LT(after_gap[0].t_s, 8.7);
  // The run's summary names the stretches; the camera's stamps run a few ms late (sensor realism), so the
  // blackout's states are read to 20 ms.
  const std::size_t blind_line = output_->output.find("vio inertial_only from ");
  ASSERT_NE(blind_line, std::string::npos) << output_->output;
  double from_s = 0, to_s = 0;
  int states = 0;
  ASSERT_EQ(std::sscanf(output_->output.c_str() + blind_line, "vio inertial_only from %lf to %lf s (%d states)", &from_s,
                        &to_s, &states),
            3);
  EXPECT_NEAR(from_s, 3.0, 0.02);
  EXPECT_NEAR(to_s, 4.95, 0.02);
  EXPECT_EQ(states, 40);
  for (const char* line : {"vio imu_gap from 6.", "lidar after_gap from 8.60 to 8.60 s (1 sweeps, 1.50 s without sweeps)"}) {
    EXPECT_NE(output_->output.find(line), std::string::npos) << line << "\n" << output_->output;
  }
}

TEST_F(SensorFaults, PosesStayOnTheTruthThroughEveryFault) {
  ASSERT_NE(output_, nullptr);
  // Measured (2026-11-29, gcc): LiDAR (loop closed) 0.022 m, VIO 0.060 m. Taken at face value, the gap's IMU
  // factor sends the VIO off; how far depends on the frontend and on the build's rounding once the window diverges
  // (VIO 0.53 m; 1.16 m with the vignetting self-calibration off; earlier builds 3.1 m), so that side is bounded
  // relative to the run with the model. The LiDAR poses it guides went off too in earlier builds (2.6 m; 0.12 m with
  // the self-calibration off); now the mapper holds them (0.024 m), so only the VIO shows what the model is for.
  const double lidar_m = ape_m("run", "lidar_final.tum", "lidar");
  const double vio_m = ape_m("run", "vio_camera.tum", "imu");
  const double face_lidar_m = ape_m("face_value", "lidar_final.tum", "lidar");
  const double face_vio_m = ape_m("face_value", "vio_camera.tum", "imu");
  std::printf("SE(3) APE: LiDAR %.4f m, VIO %.4f m; gap at face value: LiDAR %.4f m, VIO %.4f m\n", lidar_m, vio_m,
              face_lidar_m, face_vio_m);
  EXPECT_LT(lidar_m, 0.05);  // twice the fault-free lap's
  EXPECT_LT(vio_m, 0.08);
  EXPECT_GT(face_vio_m, 4.0 * vio_m);
}

}  // namespace
}  // namespace vilslam

namespace vilslam {
namespace {

// The gap at face value with the loss check on: the VIO notices that its window rejects the images, says so, drops
// the window and aligns again; the LiDAR side maps the sweeps of that stretch on its own. The LiDAR poses stay as
// close to the truth as with the gap model, and the VIO's as close as the face-value run's are far.
TEST_F(SensorFaults, TheVioDeclaresItselfLostAndStartsAgain) {
  ASSERT_NE(restarted_, nullptr);
  std::vector<CsvRow> lost, restarted;
  for (const CsvRow& r : read_status_csv(run("restarted") + "/vio_status.csv")) {
    if (r.cells.at(1).rfind("lost_", 0) == 0) lost.push_back(r);
    if (r.cells.at(1) == "restarted") restarted.push_back(r);
  }
  ASSERT_EQ(lost.size(), 1u);
  EXPECT_EQ(lost[0].cells.at(1), "lost_inconsistent");
  EXPECT_GT(lost[0].t_s, 6.0);
  EXPECT_LT(lost[0].t_s, 8.0);
  ASSERT_EQ(restarted.size(), 1u);
  EXPECT_GT(restarted[0].t_s, lost[0].t_s);
  EXPECT_LT(restarted[0].t_s, lost[0].t_s + 0.2);
  EXPECT_NE(restarted_->output.find("vio lost_inconsistent from"), std::string::npos) << restarted_->output;
  // The sweeps between the loss and the restarted window's first pose were mapped without a VIO prior.
  int without_prior = 0;
  for (const CsvRow& r : read_status_csv(run("restarted") + "/lidar_status.csv")) {
    if (r.cells.at(3) == "0") {
      ++without_prior;
      EXPECT_GT(r.t_s, lost[0].t_s - 0.2) << "a sweep without a prior before the loss";
    }
  }
  EXPECT_GT(without_prior, 0);
  const double lidar_m = ape_m("restarted", "lidar_final.tum", "lidar");
  const double vio_m = ape_m("restarted", "vio_camera.tum", "imu");
  const double face_vio_m = ape_m("face_value", "vio_camera.tum", "imu");
  std::printf("SE(3) APE after a restart: LiDAR %.4f m, VIO %.4f m (face value without the loss check: VIO %.4f m)\n",
              lidar_m, vio_m, face_vio_m);
  EXPECT_LT(lidar_m, 0.05);
  // Measured (2026-11-29): 0.147 m against the face value's 0.527 m (0.131 / 1.16 m with the vignetting
  // self-calibration off): the restarted window is aligned afresh, so it keeps an offset the run with the gap model
  // (0.060 m) does not have, but not the face value's divergence.
  EXPECT_LT(3.0 * vio_m, face_vio_m);
}

}  // namespace
}  // namespace vilslam
