// DatasetWriter output read back through open_dataset equals what was written.
#include <filesystem>

#include "common/error.h"
#include "io/cloud_io.h"
#include "io/dataset.h"
#include "synthetic_dataset.h"
#include "calibration_expect.h"
#include "test_util.h"

namespace vilslam {
namespace {

namespace fs = std::filesystem;

void expect_same_pose(const SE3& a, const SE3& b) {
  EXPECT_LT((a.matrix() - b.matrix()).cwiseAbs().maxCoeff(), 1e-14);
}

TEST(DatasetWriter, RoundTripIsExact) {
  const auto dir = test::temp_dir();
  const std::string root = (dir / "seq").string();
  const test::SyntheticData d = test::make_synthetic_data();
  test::write_synthetic_dataset(root, d);
  EXPECT_FALSE(fs::exists(root + ".partial"));

  const auto reader = open_dataset(root);
  EXPECT_EQ(reader->summary().format, "vilslam");
  EXPECT_EQ(reader->summary().stereo_frames, d.stereo.size());
  EXPECT_EQ(reader->summary().imu_samples, d.imu.size());
  EXPECT_EQ(reader->summary().lidar_scans, d.scans.size());
  EXPECT_EQ(reader->summary().groundtruth_poses, d.groundtruth.size());
  EXPECT_TRUE(reader->summary().problems.empty());
  EXPECT_NEAR(reader->summary().lidar_rate_hz, 10.0, 1e-9);

  const RigCalibration& c = reader->calibration();
  test::expect_same_camera(c.cam0, d.calib.cam0);
  test::expect_same_camera(c.cam1, d.calib.cam1);
  expect_same_pose(c.T_I_C0, d.calib.T_I_C0);
  expect_same_pose(c.T_I_C1, d.calib.T_I_C1);
  expect_same_pose(c.T_I_L, d.calib.T_I_L);
  EXPECT_TRUE(c.has_lidar);
  EXPECT_EQ(c.lidar.num_rings, 16);
  EXPECT_EQ(c.lidar.min_range_m, 0.4);
  EXPECT_EQ(c.imu.gyro_noise_density, 1.7e-4);
  EXPECT_EQ(c.cam_time_offset_ns, -1234);
  EXPECT_EQ(c.lidar_time_offset_ns, 567);

  std::size_t n_imu = 0, n_stereo = 0, n_scan = 0, n_gt = 0;
  while (auto e = reader->next()) {
    if (const auto* s = std::get_if<ImuSample>(&e->data)) {
      const ImuSample& w = d.imu[n_imu++];
      EXPECT_EQ(s->t_ns, w.t_ns);
      EXPECT_EQ(s->gyro_rad_s, w.gyro_rad_s);
      EXPECT_EQ(s->accel_m_s2, w.accel_m_s2);
    } else if (const auto* f = std::get_if<StereoFrame>(&e->data)) {
      const StereoFrame& w = d.stereo[n_stereo++];
      EXPECT_EQ(f->t_ns, w.t_ns);
      EXPECT_EQ(cv::norm(f->left, w.left, cv::NORM_INF), 0.0);
      EXPECT_EQ(cv::norm(f->right, w.right, cv::NORM_INF), 0.0);
    } else if (const auto* scan = std::get_if<LidarScan>(&e->data)) {
      const LidarScan& w = d.scans[n_scan++];
      EXPECT_EQ(scan->t_ns, w.t_ns);
      EXPECT_EQ(scan->has_ring, w.has_ring);
      ASSERT_EQ(scan->points.size(), w.points.size());
      for (std::size_t k = 0; k < w.points.size(); ++k) {
        const LidarPoint &a = scan->points[k], &b = w.points[k];
        EXPECT_TRUE(a.x == b.x && a.y == b.y && a.z == b.z && a.intensity == b.intensity &&
                    a.t_offset_s == b.t_offset_s && a.ring == b.ring) << "point " << k;
      }
    } else if (const auto* g = std::get_if<GroundTruthState>(&e->data)) {
      const GroundTruthState& w = d.groundtruth[n_gt++];
      EXPECT_EQ(g->t_ns, w.t_ns);
      expect_same_pose(g->T_W_I, w.T_W_I);
      EXPECT_EQ(g->v_W_m_s, w.v_W_m_s);
      EXPECT_EQ(g->bias_gyro_rad_s, w.bias_gyro_rad_s);
      EXPECT_EQ(g->bias_accel_m_s2, w.bias_accel_m_s2);
    }
  }
  EXPECT_EQ(n_imu, d.imu.size());
  EXPECT_EQ(n_stereo, d.stereo.size());
  EXPECT_EQ(n_scan, d.scans.size());
  EXPECT_EQ(n_gt, d.groundtruth.size());

  ASSERT_EQ(reader->reference_model_path(), (fs::path(root) / "model.ply").string());
  const PointCloud model = read_cloud(reader->reference_model_path());
  ASSERT_EQ(model.size(), d.model.size());
  for (std::size_t i = 0; i < model.size(); ++i) EXPECT_EQ(model.points[i], d.model.points[i]);
}

TEST(DatasetWriter, WithoutFinishLeavesNothing) {
  const auto dir = test::temp_dir();
  const std::string root = (dir / "seq").string();
  const test::SyntheticData d = test::make_synthetic_data();
  {
    DatasetWriter w(root, d.calib);
    w.add_imu(d.imu[0]);
    w.add_stereo(d.stereo[0]);
    EXPECT_TRUE(fs::exists(root + ".partial/mav0/cam0/data.csv"));
  }
  EXPECT_FALSE(fs::exists(root + ".partial"));
  EXPECT_FALSE(fs::exists(root));
}

TEST(DatasetWriter, RefusesExistingRootUnlessOverwrite) {
  const auto dir = test::temp_dir();
  const std::string root = (dir / "seq").string();
  const test::SyntheticData d = test::make_synthetic_data();
  test::write_synthetic_dataset(root, d);
  EXPECT_THROW(DatasetWriter(root, d.calib), InputError);
  {
    DatasetWriter w(root, d.calib, true);
    w.add_imu(d.imu[0]);
    w.add_imu(d.imu[1]);
    EXPECT_THROW(w.add_imu(d.imu[0]), std::invalid_argument);  // out of order
    w.finish();
  }
  EXPECT_EQ(open_dataset(root)->summary().imu_samples, 2u);
  EXPECT_EQ(open_dataset(root)->summary().stereo_frames, 0u);
}

TEST(DatasetWriter, WithoutRigYamlTheSensorYamlsCarryTheCalibration) {
  const auto dir = test::temp_dir();
  const std::string root = (dir / "seq").string();
  const test::SyntheticData d = test::make_synthetic_data();
  test::write_synthetic_dataset(root, d);
  fs::remove(fs::path(root) / "rig.yaml");
  const auto reader = open_dataset(root);  // still the project's format: mav0/lidar0 exists
  EXPECT_EQ(reader->summary().format, "vilslam");
  const RigCalibration& c = reader->calibration();
  test::expect_same_camera(c.cam1, d.calib.cam1);
  expect_same_pose(c.T_I_C1, d.calib.T_I_C1);
  expect_same_pose(c.T_I_L, d.calib.T_I_L);
  EXPECT_EQ(c.lidar.max_range_m, 80.0);
  EXPECT_EQ(c.imu.gyro_noise_density, 1.7e-4);
  // Without lidar0 too, the folder is plain EuRoC ASL.
  fs::remove_all(fs::path(root) / "mav0" / "lidar0");
  const auto euroc = open_dataset(root);
  EXPECT_EQ(euroc->summary().format, "euroc");
  EXPECT_EQ(euroc->summary().stereo_frames, d.stereo.size());
  EXPECT_EQ(euroc->groundtruth().size(), d.groundtruth.size());
  expect_same_pose(euroc->calibration().T_I_C0, d.calib.T_I_C0);
}

}  // namespace
}  // namespace vilslam

namespace vilslam {
namespace {

TEST(DatasetSummary, GapsLongerThanOneAndAHalfPeriodsAreProblems) {
  const auto dir = test::temp_dir();
  const std::string root = (dir / "seq").string();
  test::SyntheticData d = test::make_synthetic_data();
  d.imu.erase(d.imu.begin() + 40, d.imu.begin() + 50);  // 10 samples missing: a 55 ms step at 200 Hz
  d.stereo.erase(d.stereo.begin() + 5);                  // one frame missing: a 100 ms step at 20 Hz
  test::write_synthetic_dataset(root, d);
  const DatasetSummary s = open_dataset(root)->summary();
  ASSERT_EQ(s.problems.size(), 2u);
  EXPECT_EQ(s.problems[0], "imu0: gap of 0.055 s (11.0 periods) after t_ns=" + std::to_string(d.imu[39].t_ns));
  EXPECT_EQ(s.problems[1], "stereo: gap of 0.100 s (2.0 periods) after t_ns=" + std::to_string(d.stereo[4].t_ns));
  EXPECT_NEAR(s.imu_rate_hz, 200.0, 1e-9);
  EXPECT_NEAR(s.camera_rate_hz, 20.0, 1e-9);
  EXPECT_EQ(s.start_t_ns, d.imu.front().t_ns);
  EXPECT_EQ(s.end_t_ns, d.imu.back().t_ns);  // the latest of all streams
}

}  // namespace
}  // namespace vilslam
