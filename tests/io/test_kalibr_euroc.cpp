// A Kalibr calibration of the real EuRoC rig, written from the numbers of its sensor.yaml files, loads to
// the same calibration as the EuRoC reader gives; dropped next to the data, it is what the dataset uses.
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <filesystem>
#include <fstream>

#include "common/error.h"
#include "io/dataset_index.h"
#include "io/kalibr_calibration.h"
#include "io/yaml_util.h"
#include "calibration_expect.h"
#include "test_util.h"

namespace vilslam {
namespace {

namespace fs = std::filesystem;

// A list with the numbers as the file prints them.
std::string list(const YAML::Node& seq) {
  std::string out = "[";
  for (std::size_t i = 0; i < seq.size(); ++i) out += (i ? ", " : "") + seq[i].as<std::string>();
  return out + "]";
}

// A 4x4 matrix as Kalibr writes it (nested rows).
std::string matrix(const Mat4& M) {
  std::string out;
  for (int r = 0; r < 4; ++r) out += "  - " + yaml_list({M(r, 0), M(r, 1), M(r, 2), M(r, 3)}) + "\n";
  return out;
}

Mat4 T_BS(const YAML::Node& sensor) {
  Mat4 M;
  for (int i = 0; i < 16; ++i) M(i / 4, i % 4) = sensor["T_BS"]["data"][i].as<double>();
  return M;
}

// camchain-imucam.yaml from EuRoC's cam0/cam1 sensor.yaml files, as Kalibr would write it:
// T_cam_imu = T_BS^-1 (EuRoC's body frame is the IMU's), T_cn_cnm1 = T_C1_C0, the OpenCV key names mapped.
std::string camchain_from_euroc(const std::string& mav0) {
  std::string text;
  Mat4 T_C0_B = Mat4::Identity();
  for (int i = 0; i < 2; ++i) {
    const YAML::Node cam = YAML::LoadFile(mav0 + "/cam" + std::to_string(i) + "/sensor.yaml");
    const Mat4 T_C_B = T_BS(cam).inverse();
    text += "cam" + std::to_string(i) + ":\n  T_cam_imu:\n" + matrix(T_C_B);
    if (i == 1) text += "  T_cn_cnm1:\n" + matrix(T_C_B * T_C0_B.inverse());
    T_C0_B = T_C_B;
    const std::string model = cam["distortion_model"].as<std::string>() == "radial-tangential" ? "radtan" : "equidistant";
    text += "  cam_overlaps: [" + std::to_string(1 - i) + "]\n  camera_model: pinhole\n  distortion_coeffs: " +
            list(cam["distortion_coefficients"]) + "\n  distortion_model: " + model +
            "\n  intrinsics: " + list(cam["intrinsics"]) + "\n  resolution: " + list(cam["resolution"]) +
            "\n  rostopic: /cam" + std::to_string(i) + "/image_raw\n  timeshift_cam_imu: 0.0\n";
  }
  return text;
}

std::string imu_yaml_from_euroc(const std::string& mav0) {
  const YAML::Node imu = YAML::LoadFile(mav0 + "/imu0/sensor.yaml");
  std::string text = "imu0:\n  T_i_b:\n" + matrix(Mat4::Identity());
  for (const char* key : {"accelerometer_noise_density", "accelerometer_random_walk", "gyroscope_noise_density",
                          "gyroscope_random_walk"}) {
    text += std::string("  ") + key + ": " + imu[key].as<std::string>() + "\n";
  }
  return text + "  model: calibrated\n  rostopic: /imu0\n  time_offset: 0.0\n  update_rate: " +
         imu["rate_hz"].as<std::string>() + "\n";
}

// The EuRoC folder with Kalibr files beside it: mav0 linked, not copied.
fs::path euroc_with_kalibr(const std::string& euroc, const std::string& camchain, const std::string& imu) {
  const fs::path dir = test::temp_dir();
  fs::create_directory_symlink(fs::path(euroc) / "mav0", dir / "mav0");
  std::ofstream(dir / kKalibrCamchainFile) << camchain;
  std::ofstream(dir / kKalibrImuFile) << imu;
  return dir;
}

void expect_same_transform(const SE3& a, const SE3& b) {
  EXPECT_LT((a.matrix() - b.matrix()).cwiseAbs().maxCoeff(), 1e-12) << a.matrix() << "\n" << b.matrix();
}

TEST(KalibrEuroc, CalibrationOfTheRealRigLoadsToTheEurocReadersNumbers) {
  VILSLAM_REQUIRE_SHARED_DATA(euroc, "euroc/V1_01_easy_micro");
  const std::string mav0 = euroc + "/mav0";
  const fs::path dir = euroc_with_kalibr(euroc, camchain_from_euroc(mav0), imu_yaml_from_euroc(mav0));
  const RigCalibration ref = index_euroc(euroc).calibration;
  // The Kalibr reader alone (Kalibr files carry no camera rate).
  const RigCalibration kalibr =
      read_kalibr_camchain((dir / kKalibrCamchainFile).string(), (dir / kKalibrImuFile).string());
  EXPECT_EQ(kalibr.cam0.rate_hz, 0.0);
  // The dataset with the Kalibr files beside it: every number the same as from the sensor.yaml files.
  const RigCalibration used = index_dataset(dir.string()).calibration;
  for (const RigCalibration* c : {&kalibr, &used}) {
    SCOPED_TRACE(c == &used ? "dataset" : "reader");
    for (int i = 0; i < 2; ++i) {
      CameraIntrinsics cam = i ? c->cam1 : c->cam0;
      if (c == &kalibr) cam.rate_hz = i ? ref.cam1.rate_hz : ref.cam0.rate_hz;
      test::expect_same_camera(cam, i ? ref.cam1 : ref.cam0);
    }
    expect_same_transform(c->T_I_C0, ref.T_I_C0);
    expect_same_transform(c->T_I_C1, ref.T_I_C1);
    expect_same_transform(c->T_C0_C1(), ref.T_C0_C1());
    EXPECT_EQ(c->imu.gyro_noise_density, ref.imu.gyro_noise_density);
    EXPECT_EQ(c->imu.gyro_random_walk, ref.imu.gyro_random_walk);
    EXPECT_EQ(c->imu.accel_noise_density, ref.imu.accel_noise_density);
    EXPECT_EQ(c->imu.accel_random_walk, ref.imu.accel_random_walk);
    EXPECT_EQ(c->imu.rate_hz, ref.imu.rate_hz);
    EXPECT_EQ(c->cam_time_offset_ns, 0);
  }
}

// The Kalibr files beside the data are what the dataset uses: a changed focal length, time shift and a
// LiDAR extrinsic show up in index_dataset and `vilslam info`; a bad file is an InputError naming it (exit 2).
TEST(KalibrEuroc, FilesBesideTheDataReplaceTheLayoutsCalibration) {
  VILSLAM_REQUIRE_SHARED_DATA(euroc, "euroc/V1_01_easy_micro");
  const std::string mav0 = euroc + "/mav0";
  std::string camchain = camchain_from_euroc(mav0);
  camchain.replace(camchain.find("intrinsics: [458.654"), 20, "intrinsics: [460.5");
  camchain.replace(camchain.find("timeshift_cam_imu: 0.0"), 22, "timeshift_cam_imu: -0.0025");
  const fs::path dir = euroc_with_kalibr(euroc, camchain, imu_yaml_from_euroc(mav0));
  const SE3 T_I_L(so3::exp(Vec3(0.01, -0.02, 1.5)), Vec3(0.1, -0.05, 0.2));
  std::ofstream(dir / kLidarImuFile) << "T_lidar_imu:\n" << matrix(T_I_L.inverse().matrix())
                                     << "timeshift_lidar_imu: 0.001\nnum_rings: 32\n";
  const RigCalibration used = index_dataset(dir.string()).calibration;
  EXPECT_EQ(used.cam0.fx, 460.5);
  EXPECT_EQ(used.cam_time_offset_ns, -2'500'000);
  ASSERT_TRUE(used.has_lidar);
  expect_same_transform(used.T_I_L, T_I_L);
  EXPECT_EQ(used.lidar_time_offset_ns, 1'000'000);
  EXPECT_EQ(used.lidar.num_rings, 32);
  EXPECT_EQ(used.lidar.rate_hz, LidarIntrinsics{}.rate_hz);

  const test::CliResult info = test::run_cli("info " + dir.string());
  ASSERT_EQ(info.exit_code, 0) << info.output;
  EXPECT_NE(info.output.find("calibration: kalibr"), std::string::npos) << info.output;

  std::ofstream(dir / kLidarImuFile) << "T_lidar_imu: [1, 0, 0]\n";
  try {
    index_dataset(dir.string());
    FAIL() << "no error for a bad lidar-imu.yaml";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), (dir / kLidarImuFile).string());
  }
  const test::CliResult bad = test::run_cli("info " + dir.string());
  EXPECT_EQ(bad.exit_code, 2) << bad.output;
  EXPECT_NE(bad.output.find("error: " + (dir / kLidarImuFile).string()), std::string::npos) << bad.output;
}

}  // namespace
}  // namespace vilslam
