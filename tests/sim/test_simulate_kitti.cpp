#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "io/cloud_io.h"
#include "io/dataset.h"
#include "sim/kitti_writer.h"
#include "sim/sim_config.h"
#include "test_util.h"

namespace vilslam::sim {
namespace {

std::vector<std::vector<double>> read_rows(const std::filesystem::path& path, bool labelled) {
  std::ifstream in(path);
  std::vector<std::vector<double>> rows;
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream ss(line);
    std::string label;
    if (labelled) ss >> label;
    std::vector<double> row;
    double x;
    while (ss >> x) row.push_back(x);
    rows.push_back(row);
  }
  return rows;
}

TEST(KittiWriter, WritesScansTimesPosesAndCalib) {
  const auto dir = test::temp_dir() / "kitti";
  const RigCalibration calib = rig_calibration(SimConfig{});
  KittiWriter writer(dir.string(), calib);
  LidarScan a, b;
  a.t_ns = 5'000'000'000;
  b.t_ns = 5'100'000'000;
  a.points = {{1.f, 2.f, 3.f, 0.5f, 0.f, 0}, {4.f, 5.f, 6.f, 0.25f, 0.05f, 3}};
  b.points = {{-1.f, 0.f, 2.f, 1.f, 0.f, 1}};
  const SE3 T_W_La(so3::exp(Vec3(0, 0, 0.3)), Vec3(1, 2, 3));
  const SE3 T_W_Lb(so3::exp(Vec3(0, 0.1, 0.4)), Vec3(2, 2, 3));
  writer.add_scan(a, T_W_La);
  writer.add_scan(b, T_W_Lb);
  writer.finish();

  const PointCloud cloud = read_cloud((dir / "velodyne" / "000000.bin").string());
  ASSERT_EQ(cloud.size(), 2u);
  EXPECT_EQ(cloud.points[1], Eigen::Vector3f(4, 5, 6));
  ASSERT_EQ(cloud.intensity.size(), 2u);
  EXPECT_EQ(cloud.intensity[1], 0.25f);
  EXPECT_EQ(read_cloud((dir / "velodyne" / "000001.bin").string()).size(), 1u);

  const auto times = read_rows(dir / "times.txt", false);
  ASSERT_EQ(times.size(), 2u);
  EXPECT_NEAR(times[1][0], 0.1, 1e-9);

  const auto poses = read_rows(dir / "poses.txt", false);
  ASSERT_EQ(poses.size(), 2u);
  ASSERT_EQ(poses[1].size(), 12u);
  const Mat4 expected = (T_W_La.inverse() * T_W_Lb).matrix();
  for (int i = 0; i < 12; ++i) EXPECT_NEAR(poses[1][i], expected(i / 4, i % 4), 1e-8);
  EXPECT_NEAR(poses[0][0], 1.0, 1e-12);

  const auto lines = read_rows(dir / "calib.txt", true);
  ASSERT_EQ(lines.size(), 5u);  // P0 P1 P2 P3 Tr
  EXPECT_EQ(lines[0][0], calib.cam0.fx);
  EXPECT_NEAR(lines[1][3], -calib.cam0.fx * 0.3, 1e-9);  // P1 carries the baseline
  for (int i = 0; i < 12; ++i) EXPECT_EQ(lines[4][i], i % 5 == 0 ? 1.0 : 0.0);  // Tr = identity

  // The project's KITTI reader sees the sweeps and their LiDAR-frame poses.
  const auto reader = open_dataset(dir.string());
  EXPECT_EQ(reader->summary().lidar_scans, 2u);
  ASSERT_EQ(reader->groundtruth().size(), 2u);
  const SE3 T_L0_L1 = reader->groundtruth()[1].T_W_I;
  EXPECT_LT((T_L0_L1.matrix() - expected).norm(), 1e-7);
}

}  // namespace
}  // namespace vilslam::sim
