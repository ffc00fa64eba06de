// Broken copies of a dataset: `vilslam info` exits with 2, names the file (and line), writes no JSON.
#include <filesystem>
#include <fstream>
#include <sstream>

#include "synthetic_dataset.h"
#include "test_util.h"

namespace vilslam {
namespace {

namespace fs = std::filesystem;

std::vector<std::string> read_lines(const fs::path& path) {
  std::ifstream f(path);
  std::vector<std::string> lines;
  for (std::string line; std::getline(f, line);) lines.push_back(line);
  return lines;
}

void write_lines(const fs::path& path, const std::vector<std::string>& lines) {
  std::ofstream f(path, std::ios::trunc);
  for (const auto& line : lines) f << line << "\n";
}

// Replaces 1-based line `number` of a text file.
void set_line(const fs::path& path, std::size_t number, const std::string& text) {
  auto lines = read_lines(path);
  ASSERT_LE(number, lines.size());
  lines[number - 1] = text;
  write_lines(path, lines);
}

std::string first_file(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().string());
  std::sort(names.begin(), names.end());
  return names.at(0);
}

class BadInput : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = test::temp_dir();
    root_ = dir_ / "seq";
    test::write_synthetic_dataset(root_.string(), test::make_synthetic_data());
    mav0_ = root_ / "mav0";
  }

  // Runs info and checks the failure contract; returns the CLI output.
  std::string expect_input_error(const std::string& must_name, const std::string& extra_args = "") {
    const fs::path json = dir_ / "info.json";
    const auto r = test::run_cli("info " + root_.string() + " --json " + json.string() + " " + extra_args);
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find("error: "), std::string::npos) << r.output;
    EXPECT_NE(r.output.find(must_name), std::string::npos) << "expected '" << must_name << "' in: " << r.output;
    EXPECT_FALSE(fs::exists(json));
    EXPECT_FALSE(fs::exists(json.string() + ".tmp"));
    return r.output;
  }

  fs::path dir_, root_, mav0_;
};

TEST_F(BadInput, IntactCopyPasses) {
  const fs::path json = dir_ / "info.json";
  const auto r = test::run_cli("info --deep " + root_.string() + " --json " + json.string());
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_TRUE(fs::exists(json));
  EXPECT_NE(r.output.find("lidar_scans: 5"), std::string::npos) << r.output;
}

TEST_F(BadInput, MissingFolder) {
  root_ = dir_ / "does_not_exist";
  expect_input_error(root_.string() + ": dataset folder does not exist");
}

TEST_F(BadInput, TruncatedCsvRow) {
  set_line(mav0_ / "imu0" / "data.csv", 5, "1600000000015000000,0.1,0.2");
  expect_input_error((mav0_ / "imu0" / "data.csv").string() + ":5: truncated row");
}

TEST_F(BadInput, NonNumericCsvField) {
  set_line(mav0_ / "state_groundtruth_estimate0" / "data.csv", 4,
           "1600000000020000003,0.2,-2,0.33,1,0,0,0,1,0.5,abc,0,0,0,0,0,0");
  expect_input_error((mav0_ / "state_groundtruth_estimate0" / "data.csv").string() + ":4: field 11 is not a number");
}

TEST_F(BadInput, TimestampsOutOfOrder) {
  auto lines = read_lines(mav0_ / "imu0" / "data.csv");
  std::swap(lines[10], lines[11]);
  write_lines(mav0_ / "imu0" / "data.csv", lines);
  expect_input_error((mav0_ / "imu0" / "data.csv").string() + ":12: timestamp");
}

TEST_F(BadInput, CameraTimestampsOutOfOrder) {
  auto lines = read_lines(mav0_ / "cam0" / "data.csv");
  std::swap(lines[2], lines[3]);
  write_lines(mav0_ / "cam0" / "data.csv", lines);
  expect_input_error((mav0_ / "cam0" / "data.csv").string() + ":4:");
}

TEST_F(BadInput, MissingImageInOwnFormat) {
  const std::string png = first_file(mav0_ / "cam1" / "data");
  fs::remove(png);
  expect_input_error(png + ": image listed in");
}

TEST_F(BadInput, MissingImageInEurocIsOnlyAProblem) {
  fs::remove(root_ / "rig.yaml");
  fs::remove_all(mav0_ / "lidar0");
  const std::string png = first_file(mav0_ / "cam1" / "data");
  fs::remove(png);
  const auto r = test::run_cli("info " + root_.string());
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("stereo_frames: 9\n"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("skipped row, missing image " + png), std::string::npos) << r.output;
}

TEST_F(BadInput, CorruptPng) {
  const std::string png = first_file(mav0_ / "cam0" / "data");
  std::ofstream(png, std::ios::trunc) << "this is not a PNG";
  expect_input_error(png + ": not a PNG");
  expect_input_error(png + ": cannot decode", "--deep");
}

TEST_F(BadInput, TruncatedPng) {
  const std::string png = first_file(mav0_ / "cam1" / "data");
  fs::resize_file(png, fs::file_size(png) / 2);
  expect_input_error(png + ": corrupt PNG: truncated");
}

TEST_F(BadInput, TruncatedScanFile) {
  const std::string bin = first_file(mav0_ / "lidar0" / "data");
  fs::resize_file(bin, fs::file_size(bin) - 10);
  expect_input_error(bin + ": file has");
  expect_input_error(bin + ": file has", "--deep");
}

TEST_F(BadInput, ScanWithWrongMagic) {
  const std::string bin = first_file(mav0_ / "lidar0" / "data");
  std::fstream f(bin, std::ios::in | std::ios::out | std::ios::binary);
  f.write("VLSCAN99", 8);
  f.close();
  expect_input_error(bin + ": wrong magic");
}

TEST_F(BadInput, NanInCsv) {
  set_line(mav0_ / "imu0" / "data.csv", 3, "1600000000005000000,nan,0,0,0,9.8,0");
  expect_input_error((mav0_ / "imu0" / "data.csv").string() + ":3: field 2 is not finite");
}

TEST_F(BadInput, NanInScanPoint) {
  const std::string bin = first_file(mav0_ / "lidar0" / "data");
  const float nan = std::numeric_limits<float>::quiet_NaN();
  std::fstream f(bin, std::ios::in | std::ios::out | std::ios::binary);
  f.seekp(16 + 24 * 3 + 4);  // point 3, y
  f.write(reinterpret_cast<const char*>(&nan), sizeof nan);
  f.close();
  expect_input_error(bin + ": point 3 has a non-finite value", "--deep");
}

TEST_F(BadInput, NonOrthonormalRotationInRigYaml) {
  auto lines = read_lines(root_ / "rig.yaml");
  const auto it = std::find_if(lines.begin(), lines.end(), [](const auto& l) { return l == "  T_I_C:"; });
  ASSERT_NE(it, lines.end());
  *(it + 1) = "    - [0.5, 0, 0, 0.1]";
  write_lines(root_ / "rig.yaml", lines);
  expect_input_error((root_ / "rig.yaml").string() + ": T_I_C: rotation is not orthonormal");
}

TEST_F(BadInput, NonOrthonormalRotationInEurocSensorYaml) {
  fs::remove(root_ / "rig.yaml");
  fs::remove_all(mav0_ / "lidar0");
  const fs::path yaml = mav0_ / "cam0" / "sensor.yaml";
  auto lines = read_lines(yaml);
  const auto it = std::find_if(lines.begin(), lines.end(), [](const auto& l) { return l.rfind("  data: [", 0) == 0; });
  ASSERT_NE(it, lines.end());
  *it = "  data: [1.0, 0.001, 0.0, 0.0,";
  write_lines(yaml, lines);
  expect_input_error(yaml.string() + ": T_BS: rotation is not orthonormal");
}

}  // namespace
}  // namespace vilslam
