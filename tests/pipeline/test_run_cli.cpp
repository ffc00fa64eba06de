// `vilslam run`: output files, bit-identical reruns, bad input, all modes and --config on a simulated sequence.
#include <gtest/gtest.h>

#include <sstream>

#include <algorithm>
#include <fstream>
#include <vector>

#include "eval/trajectory_eval.h"
#include "io/dataset.h"
#include "io/trajectory_io.h"
#include "shared_simulation.h"
#include "test_util.h"

namespace vilslam {
namespace {

namespace fs = std::filesystem;

// Runs a mode twice into <mode>_a/ and <mode>_b/ and expects identical files (timings differ by nature).
void expect_deterministic(const std::string& mode, const std::string& dataset, const fs::path& dir,
                          const std::vector<std::string>& files) {
  for (const char* name : {"_a", "_b"}) {
    const test::CliResult r = test::run_cli("run --mode " + mode + " " + dataset + " --out " + (dir / (mode + name)).string());
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_EQ(r.output.find("ETA"), std::string::npos) << "progress written to a non-terminal:\n" << r.output;
  }
  for (const std::string& file : files) {
    const std::string a = test::read_file_bytes(dir / (mode + "_a") / file);
    EXPECT_FALSE(a.empty()) << file;
    EXPECT_EQ(a, test::read_file_bytes(dir / (mode + "_b") / file)) << file;
  }
  EXPECT_TRUE(fs::exists(dir / (mode + "_a") / "timings.json"));
  EXPECT_FALSE(fs::exists(dir / (mode + "_a.partial")));
}

std::size_t count_lines(const fs::path& path) {
  const std::string text = test::read_file_bytes(path);
  return static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n'));
}

// APE RMSE (m) of an estimate against ground truth after the given alignment; prints it.
double ate_rmse(const fs::path& est_path, const Trajectory& gt, eval::AlignMode align, const char* label) {
  const Trajectory est = read_trajectory(est_path.string(), TrajectoryFormat::kTum);
  eval::TrajectoryEvalConfig config;
  config.align = align;
  const eval::TrajectoryEvalReport report = eval::evaluate_trajectory(est, gt, config);
  std::printf("%s: %zu of %zu poses matched over %.2f m, ATE RMSE %.4f m\n", label, report.matched_poses, est.size(),
              report.path_length_m, report.ape.trans.rmse);
  EXPECT_GT(report.matched_poses, est.size() / 2) << label;
  return report.ape.trans.rmse;
}

const std::vector<std::string> kVioFiles = {"vio_camera.tum", "vio_imu.tum", "vio_status.csv"};
const std::vector<std::string> kLidarFiles = {"lidar.tum", "degeneracy.csv", "lidar_status.csv"};

TEST(RunCli, EurocSliceIsDeterministic) {
  VILSLAM_REQUIRE_SHARED_DATA(path, "euroc/V1_01_easy_micro");
  expect_deterministic("vio", path, test::temp_dir(), kVioFiles);
}

TEST(RunCli, LidarModesNeedScans) {
  VILSLAM_REQUIRE_SHARED_DATA(path, "euroc/V1_01_easy_micro");
  const fs::path dir = test::temp_dir();
  for (const char* mode : {"vil", "lidar-only"}) {
    EXPECT_EQ(test::run_cli(std::string("run --mode ") + mode + " " + path + " --out " + (dir / "o").string()).exit_code, 2);
  }
  EXPECT_FALSE(fs::exists(dir / "o"));
}

TEST(RunCli, BadInputExitsTwo) {
  const fs::path dir = test::temp_dir();
  EXPECT_EQ(test::run_cli("run --mode vio " + (dir / "missing").string() + " --out " + (dir / "o").string()).exit_code, 2);
  EXPECT_FALSE(fs::exists(dir / "o"));
}

// `simulate highbay --preview --seed 3` (shared with other test processes), for the tests below.
class SimulatedHighbay : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    data_ = new std::string(test::shared_simulation("highbay --preview --seed 3"));
    ASSERT_FALSE(data_->empty());
  }
  static void TearDownTestSuite() {
    delete data_;
    data_ = nullptr;
  }
  static std::string* data_;
};
std::string* SimulatedHighbay::data_ = nullptr;

TEST_F(SimulatedHighbay, AllModes) {
  const fs::path dir = test::temp_dir();
  const std::string& data = *data_;
  expect_deterministic("vio", data, dir, kVioFiles);
  expect_deterministic("vil", data, dir, kLidarFiles);
  expect_deterministic("lidar-only", data, dir, kLidarFiles);
  EXPECT_FALSE(fs::exists(dir / "lidar-only_a" / "vio_camera.tum"));
  // vil maps every sweep after the VIO's first pose; the first sweep starts before it.
  const std::size_t scans = open_dataset(data)->summary().lidar_scans;
  EXPECT_EQ(count_lines(dir / "lidar-only_a" / "lidar.tum"), scans + 1);  // + header
  EXPECT_EQ(count_lines(dir / "lidar-only_a" / "degeneracy.csv"), scans + 1);
  EXPECT_GE(count_lines(dir / "vil_a" / "lidar.tum"), scans - 1);
  EXPECT_EQ(count_lines(dir / "vil_a" / "lidar.tum"), count_lines(dir / "vil_a" / "degeneracy.csv"));
  // Every registered sweep reports its fit: a residual of centimetres, most features matched and inliers.
  std::istringstream rows(test::read_file_bytes(dir / "vil_a" / "degeneracy.csv"));
  std::string row;
  std::getline(rows, row);
  EXPECT_EQ(row, "t_ns,degenerate,eig0,eig1,eig2,eig3,eig4,eig5,rms_residual_m,matched_fraction,inlier_fraction");
  std::getline(rows, row);  // the first sweep builds the map
  while (std::getline(rows, row)) {
    std::vector<double> v;
    std::istringstream cells(row);
    for (std::string cell; std::getline(cells, cell, ',');) v.push_back(std::stod(cell));
    ASSERT_EQ(v.size(), 11u) << row;
    EXPECT_GT(v[8], 0.0) << row;
    EXPECT_LT(v[8], 0.2) << row;
    EXPECT_GT(v[9], 0.5) << row;
    EXPECT_GT(v[10], 0.5) << row;
  }

  const auto reader = open_dataset(data);
  Trajectory gt_I, gt_L;
  for (const GroundTruthState& g : reader->groundtruth()) {
    gt_I.push_back({g.t_ns, g.T_W_I});
    gt_L.push_back({g.t_ns, g.T_W_I * reader->calibration().T_I_L});
  }
  EXPECT_LT(ate_rmse(dir / "vio_a" / "vio_camera.tum", gt_I, eval::AlignMode::kPosYaw, "vio camera states"), 0.10);
  EXPECT_LT(ate_rmse(dir / "vil_a" / "lidar.tum", gt_L, eval::AlignMode::kPosYaw, "vil LiDAR poses"), 0.10);
  // LiDAR-only starts at the first sweep's frame: align in SE(3).
  EXPECT_LT(ate_rmse(dir / "lidar-only_a" / "lidar.tum", gt_L, eval::AlignMode::kSe3, "lidar-only poses"), 0.10);
}

// The number after "key": in timings.json.
double json_number(const std::string& json, const std::string& key) {
  const std::size_t at = json.find("\"" + key + "\":");
  EXPECT_NE(at, std::string::npos) << key;
  return at == std::string::npos ? -1 : std::stod(json.substr(at + key.size() + 3));
}

// A file broken in the middle of the sequence is found while the modules work on their threads: exit 2,
// the file named, no output folder, and no hang.
TEST_F(SimulatedHighbay, FileBrokenMidwayStopsTheThreadedRun) {
  const fs::path dir = test::temp_dir();
  const fs::path copy = dir / "data";
  fs::copy(*data_, copy, fs::copy_options::recursive);
  std::vector<fs::path> images;
  for (const auto& e : fs::directory_iterator(copy / "mav0" / "cam1" / "data")) images.push_back(e.path());
  ASSERT_GT(images.size(), 10u);
  std::sort(images.begin(), images.end());
  const fs::path broken = images[images.size() / 2];
  std::ofstream(broken, std::ios::binary | std::ios::trunc) << "not a png";
  const test::CliResult r = test::run_cli("run --mode vil " + copy.string() + " --out " + (dir / "o").string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find(broken.filename().string()), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir / "o"));
}

TEST_F(SimulatedHighbay, ConfigChangesTheRunAndItsCopyRepeatsIt) {
  const fs::path dir = test::temp_dir();
  const auto run = [&](const std::string& name, const std::string& config) {
    const test::CliResult r = test::run_cli("run --mode vio " + *data_ + " --out " + (dir / name).string() + config);
    EXPECT_EQ(r.exit_code, 0) << r.output;
  };
  run("default", "");
  std::ofstream(dir / "tuned.yaml") << "frontend:\n  max_corners: 120\nvio:\n  smoother:\n    window_size: 4\n";
  run("tuned", " --config " + (dir / "tuned.yaml").string());
  const std::string tuned_config = test::read_file_bytes(dir / "tuned" / "config.yaml");
  EXPECT_NE(tuned_config.find("window_size: 4"), std::string::npos) << tuned_config;
  EXPECT_NE(tuned_config.find("max_corners: 120"), std::string::npos) << tuned_config;
  EXPECT_NE(test::read_file_bytes(dir / "tuned" / "vio_camera.tum"), test::read_file_bytes(dir / "default" / "vio_camera.tum"));
  // Fewer corners per extraction (120 instead of 600): fewer stereo matches (measured: 135 instead of 352).
  EXPECT_LT(json_number(test::read_file_bytes(dir / "tuned" / "timings.json"), "matches_max"),
            0.6 * json_number(test::read_file_bytes(dir / "default" / "timings.json"), "matches_max"));
  // The run's config.yaml holds every key: given back, it repeats the run bit for bit.
  run("repeat", " --config " + (dir / "tuned" / "config.yaml").string());
  EXPECT_EQ(test::read_file_bytes(dir / "repeat" / "vio_camera.tum"), test::read_file_bytes(dir / "tuned" / "vio_camera.tum"));
  EXPECT_EQ(test::read_file_bytes(dir / "repeat" / "config.yaml"), tuned_config);
}

TEST(RunCli, BadConfigExitsTwoWithoutOutput) {
  const fs::path dir = test::temp_dir();
  std::ofstream(dir / "bad.yaml") << "vio:\n  smoother:\n    window_size: -1\n";
  std::ofstream(dir / "typo.yaml") << "vio:\n  smoother:\n    window_sise: 4\n";
  for (const char* config : {"bad.yaml", "typo.yaml", "absent.yaml"}) {
    // The dataset need not exist: the config is checked first.
    const test::CliResult r = test::run_cli("run --mode vio " + (dir / "data").string() + " --out " +
                                            (dir / "o").string() + " --config " + (dir / config).string());
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find(config), std::string::npos) << r.output;
  }
  EXPECT_FALSE(fs::exists(dir / "o"));
  EXPECT_FALSE(fs::exists(dir / "o.partial"));
}

TEST_F(SimulatedHighbay, KittiLayoutIsLidarOnly) {
  const fs::path dir = test::temp_dir();
  const std::string kitti = *data_ + "/kitti";
  EXPECT_EQ(test::run_cli("run --mode vio " + kitti + " --out " + (dir / "vio").string()).exit_code, 2);
  EXPECT_EQ(test::run_cli("run --mode vil " + kitti + " --out " + (dir / "vil").string()).exit_code, 2);
  const test::CliResult r = test::run_cli("run --mode lidar-only " + kitti + " --out " + (dir / "lidar").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_GT(count_lines(dir / "lidar" / "lidar.tum"), 1u);
}

}  // namespace
}  // namespace vilslam
