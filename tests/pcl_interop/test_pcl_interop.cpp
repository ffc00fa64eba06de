// PCL, the reference reader of PCD and a common reader of PLY, loads the files our writers produce.
#include <gtest/gtest.h>
#include <pcl/io/pcd_io.h>
#include <pcl/io/ply_io.h>
#include <pcl/point_types.h>

#include <random>

#include "io/cloud_io.h"
#include "test_util.h"

namespace vilslam {
namespace {

PointCloud random_cloud(std::size_t n) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> coord(-50.0f, 50.0f);
  PointCloud cloud;
  for (std::size_t i = 0; i < n; ++i) {
    cloud.points.emplace_back(coord(rng), coord(rng), coord(rng));
    cloud.intensity.push_back(std::abs(coord(rng)));
  }
  return cloud;
}

void expect_same_points(const PointCloud& ours, const pcl::PointCloud<pcl::PointXYZI>& theirs) {
  ASSERT_EQ(theirs.size(), ours.size());
  for (std::size_t i = 0; i < ours.size(); ++i) {
    ASSERT_EQ(theirs[i].x, ours.points[i].x()) << i;
    ASSERT_EQ(theirs[i].y, ours.points[i].y()) << i;
    ASSERT_EQ(theirs[i].z, ours.points[i].z()) << i;
    ASSERT_EQ(theirs[i].intensity, ours.intensity[i]) << i;
  }
}

TEST(PclInterop, PclLoadsOurPcd) {
  const PointCloud cloud = random_cloud(5000);
  const std::string path = (test::temp_dir() / "ours.pcd").string();
  write_cloud(path, cloud);
  pcl::PointCloud<pcl::PointXYZI> loaded;
  ASSERT_EQ(pcl::io::loadPCDFile(path, loaded), 0);
  expect_same_points(cloud, loaded);
}

TEST(PclInterop, PclLoadsOurPly) {
  const PointCloud cloud = random_cloud(5000);
  const std::string path = (test::temp_dir() / "ours.ply").string();
  write_cloud(path, cloud);
  pcl::PointCloud<pcl::PointXYZI> loaded;
  ASSERT_EQ(pcl::io::loadPLYFile(path, loaded), 0);
  expect_same_points(cloud, loaded);
}

TEST(PclInterop, WeReadWhatPclWrites) {
  const PointCloud cloud = random_cloud(2000);
  pcl::PointCloud<pcl::PointXYZI> pcl_cloud;
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    pcl::PointXYZI p;
    p.x = cloud.points[i].x();
    p.y = cloud.points[i].y();
    p.z = cloud.points[i].z();
    p.intensity = cloud.intensity[i];
    pcl_cloud.push_back(p);
  }
  const auto dir = test::temp_dir();
  for (const bool binary : {true, false}) {
    const std::string pcd = (dir / (binary ? "pcl_bin.pcd" : "pcl_ascii.pcd")).string();
    const std::string ply = (dir / (binary ? "pcl_bin.ply" : "pcl_ascii.ply")).string();
    ASSERT_EQ(pcl::io::savePCDFile(pcd, pcl_cloud, binary), 0);
    ASSERT_EQ(pcl::io::savePLYFile(ply, pcl_cloud, binary), 0);
    for (const std::string& path : {pcd, ply}) {
      SCOPED_TRACE(path);
      const PointCloud read = read_cloud(path);
      ASSERT_EQ(read.size(), cloud.size());
      ASSERT_EQ(read.intensity.size(), cloud.size());
      for (std::size_t i = 0; i < cloud.size(); ++i) {
        // PCL's ASCII writers print a limited number of digits; its binary writers keep every bit.
        ASSERT_LE((read.points[i] - cloud.points[i]).cwiseAbs().maxCoeff(), binary ? 0.0f : 1e-5f) << i;
        ASSERT_NEAR(read.intensity[i], cloud.intensity[i], binary ? 0.0f : 1e-5f) << i;
      }
    }
  }
}

}  // namespace
}  // namespace vilslam
