// ROS1 bags written by ROS's own Python writer (python3-rosbag, tests/io/rosbag_tool.py) from a dataset in
// the project's format read back event for event as that folder, in every image encoding, LiDAR layout and
// chunk compression.
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <filesystem>
#include <fstream>

#include "common/error.h"
#include "io/dataset.h"
#include "rosbag_test_util.h"
#include "synthetic_dataset.h"
#include "test_util.h"

namespace vilslam {
namespace {

namespace fs = std::filesystem;

using RosbagRead = test::RosbagFixture;

struct LayoutCase {
  const char* layout;
  const char* left;
  const char* right;
  double point_time_s;  // how exactly the layout's time field carries the folder's float32 seconds
  bool has_ring;
  const char* compression;  // of the chunks (rosbag record --bz2 / --lz4)
};

TEST_F(RosbagRead, EveryEncodingAndLayoutReadsAsTheFolder) {
  const LayoutCase cases[] = {
      {"velodyne", "mono8", "bgr8", 0.0, true, "none"},  // float32 seconds: the same numbers
      {"ouster", "rgb8", "png", 2e-9, true, "bz2"},      // uint32 ns
      {"hesai", "png", "mono8", 5e-7, true, "lz4"},      // float64 absolute seconds (~2.4e-7 s resolution at 1.6e9 s)
      {"livox", "bgr8", "rgb8", 5e-7, false, "none"},    // float64 absolute ns (256 ns resolution at 1.6e18), no ring
      {"livox_offset", "mono8", "mono8", 2e-9, false, "lz4"},  // uint32 ns since the stamp, no ring
      // 12-bit samples in 16-bit images, either byte order: scaled from the topic's 12 bits back to the grey.
      {"velodyne", "mono16", "mono16be", 0.0, true, "none"},
  };
  for (const LayoutCase& c : cases) {
    SCOPED_TRACE(c.layout);
    const std::string bag = python_bag(std::string(c.layout) + "_" + c.left, std::string("--lidar ") + c.layout + " --left " + c.left + " --right " +
                                                     c.right + " --compression " + c.compression);
    const auto from_bag = open_dataset(bag);
    const auto from_folder = open_dataset(folder_);
    EXPECT_EQ(from_bag->summary().format, "rosbag");
    const RigCalibration& calib = from_bag->calibration();
    EXPECT_EQ(calib.cam0.fx, from_folder->calibration().cam0.fx);
    EXPECT_EQ(calib.T_I_L.translation(), from_folder->calibration().T_I_L.translation());
    test::StreamTolerance tol;
    tol.point_time_s = c.point_time_s;
    tol.compare_rings = c.has_ring;
    tol.groundtruth_pose_only = true;
    const std::size_t n = test::expect_same_events(*from_folder, *from_bag, tol);
    EXPECT_EQ(n, 100u + 10u + 5u + 50u);
    from_bag->rewind();
    std::size_t scans = 0;
    while (const auto e = from_bag->next()) {
      if (const auto* s = std::get_if<LidarScan>(&e->data)) {
        EXPECT_EQ(s->has_ring, c.has_ring);
        ++scans;
      }
    }
    EXPECT_EQ(scans, 5u) << "after rewind";
  }
}

TEST_F(RosbagRead, InfoListsTopicsTypesAndLayout) {
  const std::string bag = python_bag("ouster", "--lidar ouster --left png --right mono16", false);
  const fs::path json = dir_ / "info.json";
  const auto r = test::run_cli("info " + bag + " --calib " + folder_ + "/rig.yaml --deep --json " + json.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const YAML::Node info = YAML::LoadFile(json.string());
  EXPECT_EQ(info["format"].as<std::string>(), "rosbag");
  EXPECT_EQ(info["stereo_frames"].as<int>(), 10);
  EXPECT_EQ(info["imu_samples"].as<int>(), 100);
  EXPECT_EQ(info["lidar_scans"].as<int>(), 5);
  EXPECT_EQ(info["groundtruth_poses"].as<int>(), 50);
  std::vector<std::string> topics;
  for (const auto& t : info["topics"]) topics.push_back(t.as<std::string>());
  EXPECT_EQ(topics, (std::vector<std::string>{"imu0 /imu0 sensor_msgs/Imu",
                                              "groundtruth /ground_truth geometry_msgs/PoseStamped",
                                              "cam0 /cam0/image_raw/compressed sensor_msgs/CompressedImage",
                                              "cam1 /cam1/image_raw sensor_msgs/Image mono16/12",
                                              "lidar0 /points_raw sensor_msgs/PointCloud2 ouster"}));
}

TEST_F(RosbagRead, TopicsCanBeChosenByRole) {
  const std::string bag = python_bag("swap", "--lidar velodyne");
  // The same two image topics, named the other way round: left and right come out swapped.
  DatasetOptions options;
  options.topics = {{"cam0", "/cam1/image_raw"}, {"cam1", "/cam0/image_raw"}};
  const auto swapped = open_dataset(bag, options);
  const auto folder = open_dataset(folder_);
  const auto first_frame = [](DatasetReader& r) {
    while (const auto e = r.next()) {
      if (const auto* f = std::get_if<StereoFrame>(&e->data)) return *f;
    }
    return StereoFrame{};
  };
  const StereoFrame a = first_frame(*swapped), b = first_frame(*folder);
  EXPECT_EQ(cv::norm(a.left, b.right, cv::NORM_INF), 0);
  EXPECT_EQ(cv::norm(a.right, b.left, cv::NORM_INF), 0);

  // The same choice as the calibration file's ros_topics map; an option given on top wins.
  std::ofstream(dir_ / "swap.rig.yaml", std::ios::app) << "ros_topics:\n  cam0: /cam1/image_raw\n  cam1: /cam0/image_raw\n";
  const StereoFrame c = first_frame(*open_dataset(bag));
  EXPECT_EQ(cv::norm(c.left, b.right, cv::NORM_INF), 0);
  options.topics = {{"cam0", "/cam0/image_raw"}, {"cam1", "/cam1/image_raw"}};
  const StereoFrame d = first_frame(*open_dataset(bag, options));
  EXPECT_EQ(cv::norm(d.left, b.left, cv::NORM_INF), 0);
  options.topics = {{"lidar0", "/imu0"}};
  try {
    open_dataset(bag, options);
    ADD_FAILURE() << "an Imu topic taken as lidar0";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("/imu0 (given for lidar0) is sensor_msgs/Imu"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace vilslam
