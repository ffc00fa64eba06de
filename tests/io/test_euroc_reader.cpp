// EuRoC ASL reading on the shared real data (V1_01_easy_micro, V1_02_medium_imu).
#include <fstream>
#include <sstream>

#include "common/error.h"
#include "io/dataset.h"
#include "test_util.h"

namespace vilslam {
namespace {

Mat4 euroc_T_BS_cam0() {
  Mat4 T;
  T << 0.0148655429818, -0.999880929698, 0.00414029679422, -0.0216401454975, 0.999557249008, 0.0149672133247,
      0.025715529948, -0.064676986768, -0.0257744366974, 0.00375618835797, 0.999660727178, 0.00981073058949, 0, 0, 0, 1;
  return T;
}

Mat4 euroc_T_BS_cam1() {
  Mat4 T;
  T << 0.0125552670891, -0.999755099723, 0.0182237714554, -0.0198435579556, 0.999598781151, 0.0130119051815,
      0.0251588363115, 0.0453689425024, -0.0253898008918, 0.0179005838253, 0.999517347078, 0.00786212447038, 0, 0, 0, 1;
  return T;
}

TEST(EurocReader, V1_01CountsAndCalibrationMatchTheFiles) {
  VILSLAM_REQUIRE_SHARED_DATA(root, "euroc/V1_01_easy_micro");
  const auto reader = open_dataset(root);
  const DatasetSummary& s = reader->summary();
  EXPECT_EQ(s.format, "euroc");
  EXPECT_EQ(s.stereo_frames, 95u);
  EXPECT_EQ(s.imu_samples, 29120u);
  EXPECT_EQ(s.groundtruth_poses, 28712u);
  EXPECT_EQ(s.lidar_scans, 0u);
  // The four cam1 rows without a PNG are the problems reported.
  ASSERT_EQ(s.problems.size(), 4u);
  for (const auto& p : s.problems) EXPECT_NE(p.find("cam1/data.csv"), std::string::npos) << p;
  EXPECT_NEAR(s.camera_rate_hz, 20.0, 0.01);
  EXPECT_NEAR(s.imu_rate_hz, 200.0, 0.1);

  const RigCalibration& c = reader->calibration();
  EXPECT_EQ(c.cam0.width_px, 752);
  EXPECT_EQ(c.cam0.height_px, 480);
  EXPECT_DOUBLE_EQ(c.cam0.fx, 458.654);
  EXPECT_DOUBLE_EQ(c.cam0.fy, 457.296);
  EXPECT_DOUBLE_EQ(c.cam0.cx, 367.215);
  EXPECT_DOUBLE_EQ(c.cam0.cy, 248.375);
  EXPECT_DOUBLE_EQ(c.cam1.fx, 457.587);
  EXPECT_DOUBLE_EQ(c.cam1.cy, 255.238);
  EXPECT_EQ(c.cam0.distortion, DistortionModel::kRadTan);
  ASSERT_EQ(c.cam1.distortion_coeffs.size(), 4u);
  EXPECT_DOUBLE_EQ(c.cam0.distortion_coeffs[0], -0.28340811);
  EXPECT_DOUBLE_EQ(c.cam0.distortion_coeffs[3], 1.76187114e-05);
  EXPECT_DOUBLE_EQ(c.cam1.distortion_coeffs[2], -0.00010473);
  EXPECT_DOUBLE_EQ(c.cam0.rate_hz, 20.0);
  EXPECT_DOUBLE_EQ(c.imu.gyro_noise_density, 1.6968e-04);
  EXPECT_DOUBLE_EQ(c.imu.accel_random_walk, 3.0e-3);
  // imu0 T_BS is the identity, so T_I_C = T_BS of each camera, and T_C0_C1 = T_BS0^-1 T_BS1.
  EXPECT_LT((c.T_I_C0.matrix() - euroc_T_BS_cam0()).cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_LT((c.T_I_C1.matrix() - euroc_T_BS_cam1()).cwiseAbs().maxCoeff(), 1e-9);
  const Mat4 T_C0_C1 = euroc_T_BS_cam0().inverse() * euroc_T_BS_cam1();
  EXPECT_LT((c.T_C0_C1().matrix() - T_C0_C1).cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_NEAR(c.T_C0_C1().translation().norm(), 0.110, 0.001);  // the VI-sensor's 11 cm baseline
}

TEST(EurocReader, V1_01EventsAreTimeOrderedAndImagesGrey) {
  VILSLAM_REQUIRE_SHARED_DATA(root, "euroc/V1_01_easy_micro");
  const auto reader = open_dataset(root);
  std::size_t imu = 0, stereo = 0, gt = 0;
  TimeNs last = std::numeric_limits<TimeNs>::min();
  while (auto e = reader->next()) {
    ASSERT_GE(e->t_ns, last);
    last = e->t_ns;
    if (std::holds_alternative<ImuSample>(e->data)) {
      const auto& s = std::get<ImuSample>(e->data);
      if (imu == 0) {
        EXPECT_EQ(s.t_ns, 1403715273262142976);
        EXPECT_DOUBLE_EQ(s.gyro_rad_s.x(), -0.0020943951023931952);
        EXPECT_DOUBLE_EQ(s.accel_m_s2.z(), -3.6938381666666662);
      }
      ++imu;
    } else if (std::holds_alternative<StereoFrame>(e->data)) {
      const auto& f = std::get<StereoFrame>(e->data);
      ASSERT_EQ(f.left.type(), CV_8UC1);
      ASSERT_EQ(f.right.type(), CV_8UC1);
      EXPECT_EQ(f.left.cols, 752);
      EXPECT_EQ(f.right.rows, 480);
      ++stereo;
    } else if (std::holds_alternative<GroundTruthState>(e->data)) {
      const auto& g = std::get<GroundTruthState>(e->data);
      if (gt == 0) {
        // First TUM row: 1403715274.30214 0.878612 2.142470 0.947262 -0.828459 -0.058956 -0.553641 0.060514
        EXPECT_EQ(g.t_ns, 1403715274302140000);
        EXPECT_NEAR(g.T_W_I.translation().x(), 0.878612, 1e-12);
        EXPECT_NEAR(std::abs(g.T_W_I.quat().w()), 0.060514, 1e-5);
      }
      ++gt;
    }
  }
  EXPECT_EQ(imu, 29120u);
  EXPECT_EQ(stereo, 95u);
  EXPECT_EQ(gt, 28712u);
  reader->rewind();
  const auto first = reader->next();
  ASSERT_TRUE(first);
  // Tie at the first image's time: the IMU sample comes first.
  EXPECT_TRUE(std::holds_alternative<ImuSample>(first->data));
  EXPECT_EQ(first->t_ns, 1403715273262142976);
}

TEST(EurocReader, ImuOnlyFolderWithGt0Opens) {
  VILSLAM_REQUIRE_SHARED_DATA(root, "euroc/V1_02_medium_imu");
  const auto reader = open_dataset(root);
  const DatasetSummary& s = reader->summary();
  EXPECT_EQ(s.stereo_frames, 0u);
  EXPECT_EQ(s.imu_samples, 7999u);
  EXPECT_EQ(s.groundtruth_poses, 3340u);
  ASSERT_EQ(reader->groundtruth().size(), 3340u);
  // First gt0 row: 1403715524922140000,0.515292,1.996597,0.971028,0.161869,0.790012,-0.205215,0.554587,
  //                -0.006748,-0.01478,-0.00455,-0.002153,0.020744,0.075806,-0.013337,0.103464,0.093086
  const GroundTruthState& g = reader->groundtruth().front();
  EXPECT_EQ(g.t_ns, 1403715524922140000);
  EXPECT_NEAR(g.T_W_I.translation().y(), 1.996597, 1e-12);
  const Quat q(0.161869, 0.790012, -0.205215, 0.554587);
  EXPECT_NEAR(std::abs(g.T_W_I.quat().dot(q.normalized())), 1.0, 1e-12);
  EXPECT_DOUBLE_EQ(g.v_W_m_s.x(), -0.006748);
  EXPECT_DOUBLE_EQ(g.bias_gyro_rad_s.z(), 0.075806);
  EXPECT_DOUBLE_EQ(g.bias_accel_m_s2.z(), 0.093086);
  std::size_t events = 0;
  while (reader->next()) ++events;
  EXPECT_EQ(events, 7999u + 3340u);
}

TEST(EurocReader, MissingFolderIsInputErrorNamingIt) {
  try {
    open_dataset("/nonexistent/vilslam/dataset");
    FAIL() << "no exception";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "/nonexistent/vilslam/dataset");
  }
}

TEST(InfoCli, V1_01ReportsFramesAndImuSamples) {
  VILSLAM_REQUIRE_SHARED_DATA(root, "euroc/V1_01_easy_micro");
  const auto json = test::temp_dir() / "info.json";
  const auto r = test::run_cli("info " + root + " --json " + json.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("stereo_frames: 95"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("imu_samples: 29120"), std::string::npos) << r.output;
  std::ifstream f(json);
  std::stringstream text;
  text << f.rdbuf();
  EXPECT_NE(text.str().find("\"stereo_frames\": 95,"), std::string::npos) << text.str();
  EXPECT_NE(text.str().find("\"imu_samples\": 29120,"), std::string::npos);
  EXPECT_NE(text.str().find("\"format\": \"euroc\""), std::string::npos);
  EXPECT_NE(text.str().find("\"problems\": ["), std::string::npos);
}

TEST(InfoCli, DeepDecodesEveryImage) {
  VILSLAM_REQUIRE_SHARED_DATA(root, "euroc/V1_01_easy_micro");
  const auto r = test::run_cli("info --deep " + root);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("stereo_frames: 95"), std::string::npos) << r.output;
}

}  // namespace
}  // namespace vilslam
