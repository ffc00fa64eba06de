// `vilslam run` on a ROS1 bag gives the trajectories of the folder it came from, bit for bit: a short
// simulated sequence (highbay preview, 1.5 s), as a bag written by ROS's own Python writer (mono8 and
// bgr8 images, Velodyne PointCloud2, Imu, PoseStamped) and as one written by `vilslam export-bag`.
#include <gtest/gtest.h>

#include <filesystem>

#include "rosbag_test_util.h"
#include "shared_simulation.h"
#include "test_util.h"

namespace vilslam {
namespace {

namespace fs = std::filesystem;

class RosbagRun : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new fs::path(test::process_temp_root() / "RosbagRun");
    fs::remove_all(*dir_);
    fs::create_directories(*dir_);
    folder_ = new fs::path(test::shared_simulation("highbay --preview --seed 3"));
    ASSERT_FALSE(folder_->empty());
  }
  static void TearDownTestSuite() {
    fs::remove_all(*dir_);
    delete dir_;
    delete folder_;
  }
  static fs::path folder() { return *folder_; }  // the shared simulation (read only)

  // Runs `run --mode vil` on the dataset; returns the output folder.
  static fs::path run(const std::string& dataset, const std::string& name) {
    const fs::path out = *dir_ / name;
    const auto r = test::run_cli("run --mode vil " + dataset + " --out " + out.string());
    EXPECT_EQ(r.exit_code, 0) << r.output;
    return out;
  }

  // Every trajectory and CSV of the two runs, byte for byte (not timing_samples.csv: wall times).
  static void expect_same_outputs(const fs::path& a, const fs::path& b) {
    std::size_t compared = 0;
    for (const auto& entry : fs::directory_iterator(a)) {
      const std::string ext = entry.path().extension().string();
      if ((ext != ".tum" && ext != ".csv") || entry.path().filename() == "timing_samples.csv") continue;
      const std::string bytes = test::read_file_bytes(entry.path());
      EXPECT_FALSE(bytes.empty()) << entry.path();
      EXPECT_EQ(bytes, test::read_file_bytes(b / entry.path().filename())) << entry.path().filename();
      ++compared;
    }
    EXPECT_GE(compared, 5u) << "vio_camera.tum, vio_imu.tum, lidar.tum, ..., degeneracy.csv";
  }

  static fs::path* dir_;
  static fs::path* folder_;
};

fs::path* RosbagRun::dir_ = nullptr;
fs::path* RosbagRun::folder_ = nullptr;

TEST_F(RosbagRun, PythonWrittenBagGivesTheFolderTrajectory) {
  VILSLAM_REQUIRE_PYTHON_ROSBAG();
  const fs::path bag = *dir_ / "python.bag";
  ASSERT_EQ(test::rosbag_tool("write " + folder().string() + " " + bag.string() + " --left mono8 --right bgr8 --lidar velodyne"), 0);
  fs::copy_file(folder() / "rig.yaml", *dir_ / "python.rig.yaml");
  const auto info = test::run_cli("info " + bag.string());
  ASSERT_EQ(info.exit_code, 0) << info.output;
  EXPECT_NE(info.output.find("stereo_frames: 31"), std::string::npos) << info.output;
  EXPECT_NE(info.output.find("lidar0 /points_raw sensor_msgs/PointCloud2 velodyne"), std::string::npos) << info.output;
  expect_same_outputs(run(folder().string(), "folder_run"), run(bag.string(), "python_bag_run"));
}

TEST_F(RosbagRun, ExportedBagGivesTheFolderTrajectory) {
  const fs::path bag = *dir_ / "exported.bag";
  const auto r = test::run_cli("export-bag " + folder().string() + " --out " + bag.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const fs::path folder_run = fs::exists(*dir_ / "folder_run") ? *dir_ / "folder_run" : run(folder().string(), "folder_run");
  expect_same_outputs(folder_run, run(bag.string(), "exported_bag_run"));
}

}  // namespace
}  // namespace vilslam
