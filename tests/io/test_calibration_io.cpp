// Calibration files: the project's rig YAML (round trip), Kalibr camchains, config/euroc.yaml.
#include <filesystem>
#include <fstream>

#include "common/error.h"
#include "io/calibration_io.h"
#include "io/kalibr_calibration.h"
#include "io/dataset.h"
#include "synthetic_dataset.h"
#include "test_util.h"

namespace vilslam {
namespace {

namespace fs = std::filesystem;

double pose_diff(const SE3& a, const SE3& b) { return (a.matrix() - b.matrix()).cwiseAbs().maxCoeff(); }


TEST(RigYaml, RoundTripKeepsEveryField) {
  const auto dir = test::temp_dir();
  for (const bool lidar : {true, false}) {
    RigCalibration c = test::synthetic_calibration();
    c.has_lidar = lidar;
    c.cam0.distortion = DistortionModel::kNone;
    c.cam0.distortion_coeffs.clear();
    const std::string path = (dir / "rig.yaml").string();
    write_rig_yaml(path, c);
    const RigCalibration r = read_rig_yaml(path);
    EXPECT_EQ(r.cam0.distortion, DistortionModel::kNone);
    EXPECT_TRUE(r.cam0.distortion_coeffs.empty());
    EXPECT_EQ(r.cam1.distortion, DistortionModel::kEquidistant);
    EXPECT_EQ(r.cam1.distortion_coeffs, c.cam1.distortion_coeffs);
    EXPECT_EQ(r.cam1.fx, c.cam1.fx);
    EXPECT_EQ(r.cam1.cy, c.cam1.cy);
    EXPECT_EQ(r.cam0.width_px, 64);
    EXPECT_EQ(r.cam0.rate_hz, 20);
    EXPECT_LT(pose_diff(r.T_I_C0, c.T_I_C0), 1e-15);
    EXPECT_LT(pose_diff(r.T_I_C1, c.T_I_C1), 1e-15);
    EXPECT_EQ(r.has_lidar, lidar);
    if (lidar) {
      EXPECT_LT(pose_diff(r.T_I_L, c.T_I_L), 1e-15);
      EXPECT_EQ(r.lidar.num_rings, c.lidar.num_rings);
      EXPECT_EQ(r.lidar.rate_hz, c.lidar.rate_hz);
      EXPECT_EQ(r.lidar.min_range_m, c.lidar.min_range_m);
      EXPECT_EQ(r.lidar.max_range_m, c.lidar.max_range_m);
    }
    EXPECT_EQ(r.imu.gyro_noise_density, c.imu.gyro_noise_density);
    EXPECT_EQ(r.imu.gyro_random_walk, c.imu.gyro_random_walk);
    EXPECT_EQ(r.imu.accel_noise_density, c.imu.accel_noise_density);
    EXPECT_EQ(r.imu.accel_random_walk, c.imu.accel_random_walk);
    EXPECT_EQ(r.imu.rate_hz, c.imu.rate_hz);
    EXPECT_EQ(r.cam_time_offset_ns, -1234);
    EXPECT_EQ(r.lidar_time_offset_ns, 567);
    // Writing what was read gives the same text: the format is a fixed point.
    EXPECT_EQ(rig_yaml_text(r), rig_yaml_text(read_rig_yaml(path)));
  }
}

TEST(RigYaml, MissingFieldAndBadValuesNameTheFile) {
  const auto dir = test::temp_dir();
  const fs::path path = dir / "rig.yaml";
  std::string text = rig_yaml_text(test::synthetic_calibration());
  test::write_file_bytes(path, text.substr(0, text.find("imu:")));
  try {
    read_rig_yaml(path.string());
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), path.string());
    EXPECT_NE(std::string(e.what()).find("missing section 'imu'"), std::string::npos) << e.what();
  }
  const auto pos = text.find("intrinsics: [");
  test::write_file_bytes(path, text.substr(0, pos) + "intrinsics: [-5, " + text.substr(pos + 13));
  EXPECT_THROW(read_rig_yaml(path.string()), InputError);
  test::write_file_bytes(path, text + "\n  : : [\n");
  EXPECT_THROW(read_rig_yaml(path.string()), InputError);
  const auto lidar_rate = text.find("rate_hz", text.find("lidar:"));  // per-point times come from it
  test::write_file_bytes(path, text.substr(0, lidar_rate) + "rate_hz: 0\n" + text.substr(text.find('\n', lidar_rate) + 1));
  try {
    read_rig_yaml(path.string());
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("lidar rate_hz must be positive"), std::string::npos) << e.what();
  }
}

TEST(RigYaml, EurocConfigEqualsTheDatasetCalibration) {
  VILSLAM_REQUIRE_SHARED_DATA(root, "euroc/V1_01_easy_micro");
  const RigCalibration config = read_rig_yaml(std::string(VILSLAM_SOURCE_DIR) + "/config/euroc.yaml");
  const RigCalibration data = open_dataset(root)->calibration();
  EXPECT_LT(pose_diff(config.T_I_C0, data.T_I_C0), 1e-15);
  EXPECT_LT(pose_diff(config.T_I_C1, data.T_I_C1), 1e-15);
  EXPECT_EQ(config.cam0.distortion_coeffs, data.cam0.distortion_coeffs);
  EXPECT_EQ(config.cam1.distortion_coeffs, data.cam1.distortion_coeffs);
  EXPECT_EQ(config.cam1.fx, data.cam1.fx);
  EXPECT_EQ(config.cam0.cy, data.cam0.cy);
  EXPECT_EQ(config.imu.accel_noise_density, data.imu.accel_noise_density);
  EXPECT_FALSE(config.has_lidar);
}

// A Kalibr camchain-imucam file as Kalibr writes it (EuRoC's cameras; T_cam_imu = T_BS^-1).
std::string kalibr_camchain(const SE3& T_C0_I, const SE3& T_C1_I, bool cam1_with_T_cam_imu) {
  auto rows = [](const SE3& T) {
    const Mat4 M = T.matrix();
    std::string out;
    char buf[40];
    for (int r = 0; r < 4; ++r) {
      out += "  - [";
      for (int c = 0; c < 4; ++c) {
        std::snprintf(buf, sizeof buf, "%s%.17g", c ? ", " : "", M(r, c));
        out += buf;
      }
      out += "]\n";
    }
    return out;
  };
  std::string text =
      "cam0:\n  T_cam_imu:\n" + rows(T_C0_I) +
      "  cam_overlaps: [1]\n  camera_model: pinhole\n  distortion_coeffs: [-0.28340811, 0.07395907, 0.00019359, "
      "1.76187114e-05]\n  distortion_model: radtan\n  intrinsics: [458.654, 457.296, 367.215, 248.375]\n"
      "  resolution: [752, 480]\n  rostopic: /cam0/image_raw\n"
      "cam1:\n";
  const SE3 T_C1_C0 = T_C1_I * T_C0_I.inverse();
  text += cam1_with_T_cam_imu ? "  T_cam_imu:\n" + rows(T_C1_I) : std::string();
  text += "  T_cn_cnm1:\n" + rows(T_C1_C0) +
          "  cam_overlaps: [0]\n  camera_model: pinhole\n  distortion_coeffs: [0.1, -0.02, 0.003, -0.0004]\n"
          "  distortion_model: equidistant\n  intrinsics: [457.587, 456.134, 379.999, 255.238]\n"
          "  resolution: [752, 480]\n  rostopic: /cam1/image_raw\n";
  return text;
}

TEST(KalibrCamchain, ReadsIntrinsicsAndComposesExtrinsics) {
  const auto dir = test::temp_dir();
  const SE3 T_I_C0(so3::exp(Vec3(0.02, -0.01, 1.58)), Vec3(-0.0216, -0.0647, 0.0098));
  const SE3 T_I_C1(so3::exp(Vec3(0.03, -0.01, 1.57)), Vec3(-0.0198, 0.0454, 0.0079));
  for (const bool with_T_cam_imu : {true, false}) {
    test::write_file_bytes(dir / "camchain.yaml", kalibr_camchain(T_I_C0.inverse(), T_I_C1.inverse(), with_T_cam_imu));
    test::write_file_bytes(dir / "imu.yaml",
               "accelerometer_noise_density: 0.002\naccelerometer_random_walk: 0.003\n"
               "gyroscope_noise_density: 0.00016968\ngyroscope_random_walk: 1.9393e-05\n"
               "rostopic: /imu0\nupdate_rate: 200.0\n");
    const RigCalibration c = read_kalibr_camchain((dir / "camchain.yaml").string(), (dir / "imu.yaml").string());
    EXPECT_EQ(c.cam0.fx, 458.654);
    EXPECT_EQ(c.cam1.cx, 379.999);
    EXPECT_EQ(c.cam0.width_px, 752);
    EXPECT_EQ(c.cam0.distortion, DistortionModel::kRadTan);
    EXPECT_EQ(c.cam1.distortion, DistortionModel::kEquidistant);
    EXPECT_EQ(c.cam1.distortion_coeffs, (std::vector<double>{0.1, -0.02, 0.003, -0.0004}));
    EXPECT_LT(pose_diff(c.T_I_C0, T_I_C0), 1e-12);
    EXPECT_LT(pose_diff(c.T_I_C1, T_I_C1), 1e-12);
    EXPECT_EQ(c.imu.gyro_noise_density, 0.00016968);
    EXPECT_EQ(c.imu.accel_random_walk, 0.003);
    EXPECT_EQ(c.imu.rate_hz, 200.0);
  }
}

TEST(KalibrCamchain, RejectsNonPinholeAndBadRotations) {
  const auto dir = test::temp_dir();
  const fs::path path = dir / "camchain.yaml";
  std::string text = kalibr_camchain(SE3(), SE3(Quat::Identity(), Vec3(-0.11, 0, 0)), true);
  test::write_file_bytes(path, std::string(text).replace(text.find("pinhole"), 7, "omni"));
  EXPECT_THROW(read_kalibr_camchain(path.string()), InputError);
  test::write_file_bytes(path, std::string(text).replace(text.find("  - [1, 0, 0"), 12, "  - [1, 0.2, 0"));
  try {
    read_kalibr_camchain(path.string());
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), path.string());
    EXPECT_NE(std::string(e.what()).find("T_cam_imu: rotation is not orthonormal"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace vilslam
