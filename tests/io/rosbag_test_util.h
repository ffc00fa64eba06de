#pragma once
// Helpers of the ROS bag tests: ROS's own Python bag library (Debian python3-rosbag) driven through
// tests/io/rosbag_tool.py, and comparing the event streams of two datasets.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <string>

#include "io/dataset.h"
#include "synthetic_dataset.h"
#include "test_util.h"

namespace vilslam::test {

// Debian's interpreter: python3-rosbag lives in its dist-packages only.
constexpr char kDebianPython[] = "/usr/bin/python3";

// Empty when python3-rosbag and the message packages import, else what is wrong.
inline std::string python_rosbag_problem() {
  const std::string cmd = std::string(kDebianPython) +
                          " -c 'import rosbag, sensor_msgs.msg, geometry_msgs.msg' > /dev/null 2>&1";
  if (std::system(cmd.c_str()) == 0) return {};
  return std::string(kDebianPython) +
         " cannot import rosbag, sensor_msgs and geometry_msgs: install python3-rosbag, python3-sensor-msgs and "
         "python3-geometry-msgs (./scripts/setup does)";
}

// Without python3-rosbag a test fails under CI=true (scripts/setup installs it there) and skips elsewhere,
// with the message above (the convention of the real-data tests).
#define VILSLAM_REQUIRE_PYTHON_ROSBAG()                                                          \
  if (const std::string problem = ::vilslam::test::python_rosbag_problem(); !problem.empty()) { \
    if (::vilslam::test::under_ci()) FAIL() << problem;                                         \
    GTEST_SKIP() << problem;                                                                     \
  }

// Runs tests/io/rosbag_tool.py with the given arguments; returns its exit code (output in the log).
inline int rosbag_tool(const std::string& args) {
  const std::string cmd = std::string(kDebianPython) + " " + VILSLAM_SOURCE_DIR + "/tests/io/rosbag_tool.py " + args;
  const int status = std::system(cmd.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

// A synthetic dataset folder (tests/io/synthetic_dataset.h) in a fresh temp dir, and bags written from it
// by ROS's own writer.
class RosbagFixture : public ::testing::Test {
 protected:
  void SetUp() override {
    VILSLAM_REQUIRE_PYTHON_ROSBAG();
    dir_ = temp_dir();
    folder_ = (dir_ / "synthetic").string();
    data_ = make_synthetic_data();
    write_synthetic_dataset(folder_, data_);
  }

  // A bag of the folder written by rosbag_tool.py; its calibration beside it unless with_calibration is false.
  std::string python_bag(const std::string& name, const std::string& options, bool with_calibration = true) {
    const std::string bag = (dir_ / (name + ".bag")).string();
    EXPECT_EQ(rosbag_tool("write " + folder_ + " " + bag + " " + options), 0) << options;
    if (with_calibration) std::filesystem::copy_file(std::filesystem::path(folder_) / "rig.yaml", dir_ / (name + ".rig.yaml"));
    return bag;
  }

  std::filesystem::path dir_;
  std::string folder_;
  SyntheticData data_;
};

struct StreamTolerance {
  double point_time_s = 0;  // per-point time offsets
  bool compare_rings = true;
  bool groundtruth_pose_only = false;  // a bag's PoseStamped carries no velocity or biases
};

// Every event of a and b in order: same kinds and times; IMU, images and points identical, point times
// within tolerance. Returns the number of events compared.
inline std::size_t expect_same_events(DatasetReader& a, DatasetReader& b, const StreamTolerance& tol) {
  const auto failures = [] { return ::testing::UnitTest::GetInstance()->current_test_info()->result()->total_part_count(); };
  const int failures_before = failures();
  const auto failed = [&] { return failures() > failures_before; };
  std::size_t n = 0;
  while (true) {
    const auto ea = a.next();
    const auto eb = b.next();
    EXPECT_EQ(ea.has_value(), eb.has_value()) << "after " << n << " events";
    if (!ea || !eb) break;
    ++n;
    EXPECT_EQ(ea->t_ns, eb->t_ns) << "event " << n;
    EXPECT_EQ(ea->data.index(), eb->data.index()) << "event " << n;
    if (ea->data.index() != eb->data.index()) break;
    if (const auto* ia = std::get_if<ImuSample>(&ea->data)) {
      const auto& ib = std::get<ImuSample>(eb->data);
      EXPECT_EQ(ia->gyro_rad_s, ib.gyro_rad_s);
      EXPECT_EQ(ia->accel_m_s2, ib.accel_m_s2);
    } else if (const auto* fa = std::get_if<StereoFrame>(&ea->data)) {
      const auto& fb = std::get<StereoFrame>(eb->data);
      EXPECT_EQ(cv::norm(fa->left, fb.left, cv::NORM_INF), 0) << "left image at " << fa->t_ns;
      EXPECT_EQ(cv::norm(fa->right, fb.right, cv::NORM_INF), 0) << "right image at " << fa->t_ns;
    } else if (const auto* sa = std::get_if<LidarScan>(&ea->data)) {
      const auto& sb = std::get<LidarScan>(eb->data);
      EXPECT_EQ(sa->points.size(), sb.points.size());
      for (std::size_t i = 0; i < std::min(sa->points.size(), sb.points.size()); ++i) {
        const LidarPoint &p = sa->points[i], &q = sb.points[i];
        EXPECT_EQ(p.x, q.x);
        EXPECT_EQ(p.y, q.y);
        EXPECT_EQ(p.z, q.z);
        EXPECT_EQ(p.intensity, q.intensity);
        EXPECT_NEAR(p.t_offset_s, q.t_offset_s, tol.point_time_s) << "scan at " << sa->t_ns << " point " << i;
        if (tol.compare_rings && sa->has_ring) {
          EXPECT_EQ(p.ring, q.ring);
        }
        if (failed()) return n;
      }
    } else {
      const auto& ga = std::get<GroundTruthState>(ea->data);
      const auto& gb = std::get<GroundTruthState>(eb->data);
      EXPECT_EQ(ga.T_W_I.translation(), gb.T_W_I.translation());
      EXPECT_LT(ga.T_W_I.quat().angularDistance(gb.T_W_I.quat()), 1e-12);
      if (!tol.groundtruth_pose_only) {
        EXPECT_EQ(ga.v_W_m_s, gb.v_W_m_s);
      }
    }
    if (failed()) break;
  }
  return n;
}

}  // namespace vilslam::test
