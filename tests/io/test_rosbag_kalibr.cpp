// A Kalibr calibration for a ROS1 bag (`--calib camchain-imucam[-NAME].yaml`, docs/formats.md): the rig's
// numbers written as Kalibr files load to the same calibration, the bag then reads as its folder, Kalibr's
// rostopic keys choose the topics, and a camchain without IMU noise is refused for a bag. The same
// `--calib` on a folder replaces only what the Kalibr files hold.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>

#include "common/error.h"
#include "io/calibration_io.h"
#include "io/dataset.h"
#include "io/yaml_util.h"
#include "calibration_expect.h"
#include "rosbag_test_util.h"

namespace vilslam {
namespace {

namespace fs = std::filesystem;

// A 4x4 transform as Kalibr writes it (nested rows).
std::string kalibr_matrix(const SE3& T) {
  const std::vector<double> e = transform_entries(T);
  std::string out;
  for (int r = 0; r < 4; ++r) out += "  - " + yaml_list({e[4 * r], e[4 * r + 1], e[4 * r + 2], e[4 * r + 3]}) + "\n";
  return out;
}

struct KalibrTopics {
  std::string cam0 = "/cam0/image_raw", cam1 = "/cam1/image_raw", imu0 = "/imu0", lidar0 = "/points_raw";
};

// The calibration as Kalibr's result files named after a run (camchain-imucam-NAME.yaml, imu-NAME.yaml,
// and the project's lidar-imu-NAME.yaml); with_imu false leaves out the IMU file. Returns the camchain.
std::string write_kalibr(const RigCalibration& c, const fs::path& dir, const std::string& name,
                         const KalibrTopics& topics = {}, bool with_imu = true) {
  const CameraIntrinsics* cams[2] = {&c.cam0, &c.cam1};
  const SE3* T_I_C[2] = {&c.T_I_C0, &c.T_I_C1};
  const std::string cam_topics[2] = {topics.cam0, topics.cam1};
  std::string camchain;
  for (int i = 0; i < 2; ++i) {
    const CameraIntrinsics& k = *cams[i];
    camchain += "cam" + std::to_string(i) + ":\n  T_cam_imu:\n" + kalibr_matrix(T_I_C[i]->inverse()) +
                "  camera_model: pinhole\n  distortion_coeffs: " + yaml_list(k.distortion_coeffs) +
                "\n  distortion_model: " + distortion_model_name(k.distortion) + "\n  intrinsics: " +
                yaml_list({k.fx, k.fy, k.cx, k.cy}) + "\n  resolution: [" + std::to_string(k.width_px) + ", " +
                std::to_string(k.height_px) + "]\n  rostopic: " + cam_topics[i] +
                "\n  timeshift_cam_imu: " + yaml_number(c.cam_time_offset_ns * 1e-9) + "\n";
  }
  const fs::path camchain_path = dir / ("camchain-imucam-" + name + ".yaml");
  std::ofstream(camchain_path) << camchain;
  if (with_imu) {
    std::ofstream(dir / ("imu-" + name + ".yaml"))
        << "imu0:\n  accelerometer_noise_density: " << yaml_number(c.imu.accel_noise_density)
        << "\n  accelerometer_random_walk: " << yaml_number(c.imu.accel_random_walk)
        << "\n  gyroscope_noise_density: " << yaml_number(c.imu.gyro_noise_density)
        << "\n  gyroscope_random_walk: " << yaml_number(c.imu.gyro_random_walk)
        << "\n  rostopic: " << topics.imu0 << "\n  update_rate: " << yaml_number(c.imu.rate_hz) << "\n";
  }
  std::ofstream(dir / ("lidar-imu-" + name + ".yaml"))
      << "T_lidar_imu:\n" << kalibr_matrix(c.T_I_L.inverse()) << "timeshift_lidar_imu: "
      << yaml_number(c.lidar_time_offset_ns * 1e-9) << "\nnum_rings: " << c.lidar.num_rings
      << "\nrate_hz: " << yaml_number(c.lidar.rate_hz) << "\nmin_range_m: " << yaml_number(c.lidar.min_range_m)
      << "\nmax_range_m: " << yaml_number(c.lidar.max_range_m) << "\nrostopic: " << topics.lidar0 << "\n";
  return camchain_path.string();
}

void expect_same_transform(const SE3& a, const SE3& b) {
  EXPECT_LT((a.matrix() - b.matrix()).cwiseAbs().maxCoeff(), 1e-12) << a.matrix() << "\n" << b.matrix();
}

using RosbagKalibr = test::RosbagFixture;

TEST_F(RosbagKalibr, CamchainCalibratesABagAsItsRigYamlDoes) {
  const std::string bag = python_bag("run1", "--lidar velodyne", false);
  const RigCalibration rig = read_rig_yaml(folder_ + "/rig.yaml");
  DatasetOptions options;
  options.calibration_path = write_kalibr(rig, dir_, "run1");
  const auto from_bag = open_dataset(bag, options);
  EXPECT_EQ(from_bag->summary().calibration, "kalibr " + options.calibration_path);
  const RigCalibration& c = from_bag->calibration();
  for (auto [got, want] : {std::pair{c.cam0, rig.cam0}, std::pair{c.cam1, rig.cam1}}) {
    want.rate_hz = 0;  // Kalibr files carry no camera rate
    test::expect_same_camera(got, want);
  }
  expect_same_transform(c.T_I_C0, rig.T_I_C0);
  expect_same_transform(c.T_I_C1, rig.T_I_C1);
  expect_same_transform(c.T_I_L, rig.T_I_L);
  EXPECT_EQ(c.cam_time_offset_ns, rig.cam_time_offset_ns);
  EXPECT_EQ(c.lidar_time_offset_ns, rig.lidar_time_offset_ns);
  EXPECT_EQ(c.imu.gyro_noise_density, rig.imu.gyro_noise_density);
  EXPECT_EQ(c.imu.accel_random_walk, rig.imu.accel_random_walk);
  EXPECT_EQ(c.imu.rate_hz, rig.imu.rate_hz);
  EXPECT_EQ(c.lidar.num_rings, rig.lidar.num_rings);
  EXPECT_EQ(c.lidar.max_range_m, rig.lidar.max_range_m);
  test::StreamTolerance tol;
  tol.groundtruth_pose_only = true;
  EXPECT_EQ(test::expect_same_events(*open_dataset(folder_), *from_bag, tol), 100u + 10u + 5u + 50u);
}

TEST_F(RosbagKalibr, RostopicKeysChooseTheTopicsUnderTheOptions) {
  const std::string bag = python_bag("swapped", "--lidar velodyne", false);
  KalibrTopics swapped;
  std::swap(swapped.cam0, swapped.cam1);
  DatasetOptions options;
  options.calibration_path = write_kalibr(read_rig_yaml(folder_ + "/rig.yaml"), dir_, "swapped", swapped);
  const auto listed = [&] {
    const auto topics = open_dataset(bag, options)->summary().topics;
    return std::vector<std::string>(topics.begin(), topics.end());
  };
  auto topics = listed();
  EXPECT_NE(std::find(topics.begin(), topics.end(), "cam0 /cam1/image_raw sensor_msgs/Image mono8"), topics.end());
  options.topics = {{"cam0", "/cam0/image_raw"}, {"cam1", "/cam1/image_raw"}};  // an option wins
  topics = listed();
  EXPECT_NE(std::find(topics.begin(), topics.end(), "cam0 /cam0/image_raw sensor_msgs/Image mono8"), topics.end());
  // A rostopic naming a topic the bag does not have is refused, naming it.
  KalibrTopics missing;
  missing.imu0 = "/imu/data";
  options.topics.clear();
  options.calibration_path = write_kalibr(read_rig_yaml(folder_ + "/rig.yaml"), dir_, "missing", missing);
  try {
    open_dataset(bag, options);
    ADD_FAILURE() << "a missing IMU topic was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("/imu/data"), std::string::npos) << e.what();
  }
}

TEST_F(RosbagKalibr, CamchainWithoutImuNoiseIsRefusedForABag) {
  const std::string bag = python_bag("noimu", "--lidar velodyne", false);
  DatasetOptions options;
  options.calibration_path = write_kalibr(read_rig_yaml(folder_ + "/rig.yaml"), dir_, "noimu", {}, false);
  try {
    open_dataset(bag, options);
    ADD_FAILURE() << "a bag without IMU noise was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(options.calibration_path), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("imu-NAME.yaml"), std::string::npos) << e.what();
  }
}

TEST_F(RosbagKalibr, CamchainOnAFolderReplacesOnlyWhatItsFilesHold) {
  RigCalibration changed = read_rig_yaml(folder_ + "/rig.yaml");
  changed.cam0.fx += 1.5;
  changed.imu.gyro_noise_density *= 3;  // not written: the folder's noise stays
  DatasetOptions options;
  options.calibration_path = write_kalibr(changed, dir_, "folder", {}, false);
  const auto reader = open_dataset(folder_, options);
  EXPECT_EQ(reader->summary().calibration, "kalibr " + options.calibration_path);
  EXPECT_EQ(reader->calibration().cam0.fx, changed.cam0.fx);
  EXPECT_EQ(reader->calibration().cam0.rate_hz, read_rig_yaml(folder_ + "/rig.yaml").cam0.rate_hz);
  EXPECT_EQ(reader->calibration().imu.gyro_noise_density, read_rig_yaml(folder_ + "/rig.yaml").imu.gyro_noise_density);
}

}  // namespace
}  // namespace vilslam
