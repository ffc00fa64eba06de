// `vilslam export-bag`: the bag is read back by ROS's own Python library (python3-rosbag) with the counts,
// types, stamps and values of the dataset, and by vilslam itself event for event.
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <filesystem>

#include "io/calibration_io.h"
#include "io/dataset.h"
#include "rosbag_test_util.h"
#include "synthetic_dataset.h"
#include "test_util.h"

namespace vilslam {
namespace {

namespace fs = std::filesystem;

class RosbagExport : public test::RosbagFixture {
 protected:
  void SetUp() override {
    RosbagFixture::SetUp();
    if (IsSkipped() || HasFailure()) return;
    bag_ = (dir_ / "out.bag").string();
    const auto r = test::run_cli("export-bag " + folder_ + " --out " + bag_);
    ASSERT_EQ(r.exit_code, 0) << r.output;
  }

  std::string bag_;
};

template <typename T>
std::vector<TimeNs> stamps_of(const std::vector<T>& items) {
  std::vector<TimeNs> t;
  for (const T& item : items) t.push_back(item.t_ns);
  return t;
}

std::vector<TimeNs> as_times(const YAML::Node& list) {
  std::vector<TimeNs> t;
  for (const auto& v : list) t.push_back(v.as<TimeNs>());
  return t;
}

TEST_F(RosbagExport, PythonRosbagReadsCountsTypesStampsAndValues) {
  const fs::path json = dir_ / "dump.json";
  ASSERT_EQ(test::rosbag_tool("dump " + bag_ + " " + json.string()), 0);
  const YAML::Node topics = YAML::LoadFile(json.string());
  ASSERT_EQ(topics.size(), 5u);

  const YAML::Node imu = topics["/imu0"];
  EXPECT_EQ(imu["type"].as<std::string>(), "sensor_msgs/Imu");
  EXPECT_EQ(imu["count"].as<std::size_t>(), data_.imu.size());
  EXPECT_EQ(as_times(imu["stamps"]), stamps_of(data_.imu));
  EXPECT_EQ(as_times(imu["record_times"]), stamps_of(data_.imu));
  for (std::size_t i = 0; i < data_.imu.size(); ++i) {
    const YAML::Node v = imu["values"][i];
    for (int k = 0; k < 3; ++k) {
      EXPECT_EQ(v[k].as<double>(), data_.imu[i].gyro_rad_s[k]);
      EXPECT_EQ(v[3 + k].as<double>(), data_.imu[i].accel_m_s2[k]);
    }
    EXPECT_EQ(v[6].as<double>(), -1.0) << "orientation_covariance[0] marks no orientation";
  }

  for (const char* cam : {"/cam0/image_raw", "/cam1/image_raw"}) {
    SCOPED_TRACE(cam);
    const YAML::Node images = topics[cam];
    EXPECT_EQ(images["type"].as<std::string>(), "sensor_msgs/Image");
    EXPECT_EQ(as_times(images["stamps"]), stamps_of(data_.stereo));
    for (std::size_t i = 0; i < data_.stereo.size(); ++i) {
      const cv::Mat& grey = std::string(cam) == "/cam0/image_raw" ? data_.stereo[i].left : data_.stereo[i].right;
      const YAML::Node v = images["values"][i];
      EXPECT_EQ(v["encoding"].as<std::string>(), "mono8");
      EXPECT_EQ(v["width"].as<int>(), grey.cols);
      EXPECT_EQ(v["height"].as<int>(), grey.rows);
      EXPECT_EQ(v["step"].as<int>(), grey.cols);
      EXPECT_EQ(v["pixel_sum"].as<double>(), cv::sum(grey)[0]);
      for (int k = 0; k < 8; ++k) EXPECT_EQ(v["first_pixels"][k].as<int>(), grey.at<std::uint8_t>(0, k));
    }
  }

  const YAML::Node clouds = topics["/lidar0/points"];
  EXPECT_EQ(clouds["type"].as<std::string>(), "sensor_msgs/PointCloud2");
  EXPECT_EQ(as_times(clouds["stamps"]), stamps_of(data_.scans));
  for (std::size_t i = 0; i < data_.scans.size(); ++i) {
    const LidarScan& scan = data_.scans[i];
    const YAML::Node v = clouds["values"][i];
    EXPECT_EQ(v["width"].as<std::size_t>(), scan.points.size());
    EXPECT_EQ(v["height"].as<int>(), 1);
    EXPECT_FALSE(v["is_bigendian"].as<bool>());
    // Velodyne's PointcloudXYZIRT: x y z intensity float32, ring uint16, time float32 (ring left out without rings).
    std::vector<std::string> names;
    for (const auto& f : v["fields"]) names.push_back(f[0].as<std::string>());
    if (scan.has_ring) {
      EXPECT_EQ(names, (std::vector<std::string>{"x", "y", "z", "intensity", "ring", "time"}));
      EXPECT_EQ(v["fields"][4][1].as<int>(), 16);
      EXPECT_EQ(v["fields"][4][2].as<int>(), 4) << "ring is UINT16";
      EXPECT_EQ(v["point_step"].as<int>(), 22);
    } else {
      EXPECT_EQ(names, (std::vector<std::string>{"x", "y", "z", "intensity", "time"}));
      EXPECT_EQ(v["point_step"].as<int>(), 20);
    }
    for (std::size_t k = 0; k < 3; ++k) {
      const YAML::Node p = v["points"][k];
      const LidarPoint& q = scan.points[k];
      EXPECT_EQ(p["x"].as<float>(), q.x);
      EXPECT_EQ(p["y"].as<float>(), q.y);
      EXPECT_EQ(p["z"].as<float>(), q.z);
      EXPECT_EQ(p["intensity"].as<float>(), q.intensity);
      EXPECT_EQ(p["time"].as<float>(), q.t_offset_s);
      if (scan.has_ring) {
        EXPECT_EQ(p["ring"].as<int>(), q.ring);
      }
    }
  }

  const YAML::Node poses = topics["/groundtruth/pose"];
  EXPECT_EQ(poses["type"].as<std::string>(), "geometry_msgs/PoseStamped");
  EXPECT_EQ(as_times(poses["stamps"]), stamps_of(data_.groundtruth));
  for (std::size_t i = 0; i < data_.groundtruth.size(); ++i) {
    const SE3& T = data_.groundtruth[i].T_W_I;
    const YAML::Node v = poses["values"][i];
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(v[k].as<double>(), T.translation()[k], 1e-15);
    const Quat q(v[6].as<double>(), v[3].as<double>(), v[4].as<double>(), v[5].as<double>());
    EXPECT_LT(q.angularDistance(T.quat()), 1e-12);
  }
}

TEST_F(RosbagExport, ReadsBackAsTheDatasetWithItsCalibration) {
  ASSERT_TRUE(fs::exists(dir_ / "out.rig.yaml"));
  // The calibration as the folder's reader gives it, written as rig YAML.
  EXPECT_EQ(test::read_file_bytes(dir_ / "out.rig.yaml"), rig_yaml_text(read_rig_yaml(folder_ + "/rig.yaml")));
  const auto from_bag = open_dataset(bag_);
  const auto from_folder = open_dataset(folder_);
  test::StreamTolerance tol;
  tol.groundtruth_pose_only = true;
  EXPECT_EQ(test::expect_same_events(*from_folder, *from_bag, tol), 165u);
}

TEST_F(RosbagExport, RefusesToReplaceAndLeavesNoPartialFile) {
  const auto again = test::run_cli("export-bag " + folder_ + " --out " + bag_);
  EXPECT_EQ(again.exit_code, 2) << again.output;
  EXPECT_NE(again.output.find(bag_), std::string::npos);
  const auto bad_out = test::run_cli("export-bag " + folder_ + " --out " + (dir_ / "no_such_dir" / "x.bag").string());
  EXPECT_NE(bad_out.exit_code, 0);
  EXPECT_FALSE(fs::exists(dir_ / "no_such_dir"));
  const auto replaced = test::run_cli("export-bag " + folder_ + " --out " + bag_ + " --overwrite --no-groundtruth");
  ASSERT_EQ(replaced.exit_code, 0) << replaced.output;
  EXPECT_EQ(open_dataset(bag_)->summary().groundtruth_poses, 0u);
  for (const auto& entry : fs::directory_iterator(dir_)) {
    EXPECT_EQ(entry.path().string().find(".partial"), std::string::npos) << entry.path();
  }
}

}  // namespace
}  // namespace vilslam
