// `vilslam report` on a hand-made run folder (tests/report/synthetic_run.h): the errors are those of
// `vilslam eval`, events and timings are all there, paths are decimated, the same inputs give the same bytes,
// missing pieces leave a note, and bad input exits 2 naming the file without writing the page.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <numeric>
#include <sstream>

#include "eval/trajectory_eval.h"
#include "io/cloud_io.h"
#include "report/synthetic_run.h"
#include "test_util.h"

namespace vilslam {
namespace {

namespace fs = std::filesystem;

// The number after the first "key": following `from` in doc.
double number_after(const std::string& doc, const std::string& key, std::size_t from = 0) {
  const std::size_t at = doc.find("\"" + key + "\":", from);
  EXPECT_NE(at, std::string::npos) << key;
  return at == std::string::npos ? -1 : std::stod(doc.substr(at + key.size() + 3));
}

// The string value of the first "key": following `from` in doc.
std::string string_after(const std::string& doc, const std::string& key, std::size_t from = 0) {
  const std::size_t at = doc.find("\"" + key + "\": \"", from);
  if (at == std::string::npos) return {};
  const std::size_t begin = at + key.size() + 5;
  return doc.substr(begin, doc.find('"', begin) - begin);
}

// The report's data: the JSON inside <script id="report-data">.
std::string report_data(const std::string& html) {
  const std::size_t begin = html.find("id=\"report-data\">");
  EXPECT_NE(begin, std::string::npos);
  return html.substr(begin, html.find("</script>", begin) - begin);
}

class ReportCli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = test::temp_dir();
    run_ = dir_ / "run";
    gt_ = dir_ / "gt.tum";
    test::write_synthetic_run(run_, gt_);
  }
  test::CliResult report(const std::string& args, const fs::path& out) {
    return test::run_cli("report " + args + " --out " + out.string());
  }
  fs::path dir_, run_, gt_;
};

TEST_F(ReportCli, ErrorsAreThoseOfEval) {
  const test::CliResult r = report(run_.string() + " --gt " + gt_.string(), dir_ / "r.html");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::string data = report_data(test::read_file_bytes(dir_ / "r.html"));
  const Trajectory gt = read_trajectory(gt_.string(), TrajectoryFormat::kTum);
  const std::vector<std::pair<std::string, eval::AlignMode>> expected = {
      {"vio_camera.tum", eval::AlignMode::kPosYaw}, {"lidar.tum", eval::AlignMode::kSe3},
      {"lidar_final.tum", eval::AlignMode::kSe3}};
  for (const auto& [file, align] : expected) {
    const std::size_t at = data.find("\"file\": \"" + file + "\"");
    ASSERT_NE(at, std::string::npos) << file;
    eval::TrajectoryEvalConfig config;
    config.align = align;
    const eval::TrajectoryEvalReport e =
        eval::evaluate_trajectory(read_trajectory((run_ / file).string(), TrajectoryFormat::kTum), gt, config);
    EXPECT_GT(e.ape.trans.rmse, 0.005) << file;  // the estimates carry an error, not just another world
    EXPECT_NEAR(number_after(data, "rmse_m", at), e.ape.trans.rmse, 1e-9) << file;
    EXPECT_NEAR(number_after(data, "max_m", at), e.ape.trans.max, 1e-9) << file;
    EXPECT_EQ(number_after(data, "matched", at), static_cast<double>(e.matched_poses)) << file;
    EXPECT_EQ(string_after(data, "align", at), eval::align_mode_name(align)) << file;
  }
}

TEST_F(ReportCli, EventsAndTimingsAreAllThere) {
  const test::CliResult r = report(run_.string() + " --gt " + gt_.string(), dir_ / "r.html");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::string data = report_data(test::read_file_bytes(dir_ / "r.html"));
  EXPECT_EQ(string_after(data, "on"), "LiDAR loop-closed");
  EXPECT_EQ(number_after(data, "sweeps"), test::kSyntheticPoses);
  EXPECT_EQ(number_after(data, "degenerate"), test::kSyntheticPoses / test::kSyntheticDegenerateEvery);
  EXPECT_EQ(number_after(data, "from_t_s"), 0.5);  // the loop from pose 5 to pose 195, 0.1 s apart
  EXPECT_NEAR(number_after(data, "to_t_s"), 19.5, 1e-12);
  EXPECT_EQ(number_after(data, "realtime_speed"), 1.0);
  const std::size_t lost = data.find("\"lidar_lost_s\": [");  // when LiDAR mapping was lost, from the first pose at 1 s
  ASSERT_NE(lost, std::string::npos);
  EXPECT_EQ(std::stod(data.substr(data.find_first_of("0123456789", lost))), 12.25);
  EXPECT_EQ(number_after(data, "median_ms", data.find("\"series\": \"imu_pose_latency\"")), 0.56);
  for (const char* series : {"frontend", "lidar_mapping", "imu_pose_latency"}) {
    const std::size_t at = data.find("\"series\": \"" + std::string(series) + "\"", data.find("\"histograms\""));
    ASSERT_NE(at, std::string::npos) << series;
    const std::size_t open = data.find('[', at), close = data.find(']', at);
    std::istringstream counts(data.substr(open + 1, close - open - 1));
    std::size_t total = 0, bins = 0;
    for (std::string c; std::getline(counts, c, ',');) total += std::stoul(c), ++bins;
    EXPECT_EQ(total, static_cast<std::size_t>(test::kSyntheticPoses)) << series;
    EXPECT_EQ(bins, 40u) << series;
  }
}

TEST_F(ReportCli, PathsAreDecimatedAndTheOutputRepeats) {
  for (const char* name : {"a.html", "b.html"}) {
    const test::CliResult r = report(run_.string() + " --gt " + gt_.string() + " --max-path-points 50", dir_ / name);
    ASSERT_EQ(r.exit_code, 0) << r.output;
  }
  const std::string html = test::read_file_bytes(dir_ / "a.html");
  EXPECT_EQ(html, test::read_file_bytes(dir_ / "b.html"));
  const std::string data = report_data(html);
  const std::size_t at = data.find("\"file\": \"lidar.tum\"");
  EXPECT_EQ(number_after(data, "poses", at), test::kSyntheticPoses);
  // Every 4th of 200 poses and the last: 51 poses of 3 float32 = 612 bytes, 816 base64 characters.
  EXPECT_EQ(string_after(data, "xyz", at).size(), 816u);
  EXPECT_EQ(string_after(data, "t_s", at).size(), 4u * 51 * 4 / 3);
}

TEST_F(ReportCli, MissingPiecesLeaveNotes) {
  fs::remove(run_ / "loops.csv");
  fs::remove(run_ / "timing_samples.csv");
  const test::CliResult r = report(run_.string(), dir_ / "r.html");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::string data = report_data(test::read_file_bytes(dir_ / "r.html"));
  for (const char* note : {"no ground truth given (--gt)", "no loops.csv", "no timing_samples.csv", "no map given (--map)"})
    EXPECT_NE(data.find(note), std::string::npos) << note;
  for (const char* key : {"\"ground_truth\"", "\"errors\"", "\"loops\"", "\"map\""})
    EXPECT_EQ(data.find(key), std::string::npos) << key;
}

TEST_F(ReportCli, MapIsDecimatedAndMeasuredAgainstTheModel) {
  PointCloud grid;
  for (int i = 0; i < 100; ++i)
    for (int j = 0; j < 100; ++j) grid.points.emplace_back(0.1f * i, 0.1f * j, 0.02f * static_cast<float>((i * j) % 17));
  write_cloud((dir_ / "map.ply").string(), grid);
  const std::string args = run_.string() + " --map " + (dir_ / "map.ply").string() + " --max-map-points 2000";
  ASSERT_EQ(report(args, dir_ / "height.html").exit_code, 0);
  const std::string height = report_data(test::read_file_bytes(dir_ / "height.html"));
  EXPECT_EQ(string_after(height, "value_name"), "height_m");
  EXPECT_EQ(number_after(height, "total_points"), 10000);
  EXPECT_EQ(number_after(height, "shown_points"), 2001);  // every 5th and the last
  const test::CliResult r = report(args + " --model " + (dir_ / "map.ply").string(), dir_ / "mre.html");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::string mre = report_data(test::read_file_bytes(dir_ / "mre.html"));
  EXPECT_EQ(string_after(mre, "value_name"), "mre_m");
  EXPECT_LT(number_after(mre, "mre_p95_m"), 1e-4);  // the map is its own model
}

// Each case: exit code 2, the message names the file, and no page is written.
TEST_F(ReportCli, BadInputExitsTwoWithoutOutput) {
  const fs::path out = dir_ / "r.html";
  auto expect_refused = [&](const std::string& args, const std::string& named) {
    const test::CliResult r = report(args, out);
    EXPECT_EQ(r.exit_code, 2) << args << "\n" << r.output;
    EXPECT_NE(r.output.find(named), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(out)) << args;
  };
  expect_refused((dir_ / "absent").string(), "absent: no such run folder");
  expect_refused(run_.string() + " --gt " + (dir_ / "absent.tum").string(), "absent.tum");
  expect_refused(run_.string() + " --model " + gt_.string(), "--model");
  expect_refused(run_.string() + " --map " + (dir_ / "absent.ply").string(), "absent.ply");

  // A ground truth of other times: no estimate can be aligned with it.
  Trajectory later = read_trajectory(gt_.string(), TrajectoryFormat::kTum);
  for (TimedPose& p : later) p.t_ns += 1'000'000'000'000;
  write_trajectory((dir_ / "later.tum").string(), later, TrajectoryFormat::kTum);
  expect_refused(run_.string() + " --gt " + (dir_ / "later.tum").string(), "run: no trajectory to draw");

  const std::string lidar = test::read_file_bytes(run_ / "lidar.tum");
  std::ofstream(run_ / "lidar.tum") << "# t x y z qx qy qz qw\n1.0 0 0 0 0 0 0 1\n2.0 0 zero 0 0 0 0 1\n";
  expect_refused(run_.string(), "lidar.tum:3");
  std::ofstream(run_ / "lidar.tum") << lidar;

  std::ofstream(run_ / "degeneracy.csv") << "1,0,1,2,3,4,5,6,0.1,1,1\n";
  expect_refused(run_.string(), "degeneracy.csv: expected the header");
  fs::remove(run_ / "degeneracy.csv");

  std::ofstream(run_ / "timings.json") << "{\"mode\": \"vil\", \"data_s\": 3, \"run_wall_s\": [";
  expect_refused(run_.string(), "timings.json");
  std::ofstream(run_ / "timings.json") << "{\"mode\": \"vil\", \"data_s\": \"long\", \"run_wall_s\": 1}";
  expect_refused(run_.string(), "timings.json: 'data_s' is not a number");
  std::ofstream(run_ / "timings.json") << "{\"mode\": \"vil\", \"data_s\": 3, \"run_wall_s\": 1, \"lidar_lost_t_ns\": [\"soon\"]}";
  expect_refused(run_.string(), "timings.json: 'lidar_lost_t_ns' holds a value that is not an integer time stamp");
  fs::remove(run_ / "timings.json");
  expect_refused(run_.string(), "timings.json: missing");
}

}  // namespace
}  // namespace vilslam
