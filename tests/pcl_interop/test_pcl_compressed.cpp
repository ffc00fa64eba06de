// PCD DATA binary_compressed: the five real pjlab scans read point for point as PCL reads them, and
// clouds PCL's own writer compresses (its LZF compressor) with odd field layouts read back exactly.
#define PCL_NO_PRECOMPILE
#include <gtest/gtest.h>
#include <pcl/io/pcd_io.h>
#include <pcl/point_types.h>

#include <cstdint>
#include <cstring>

#include "io/cloud_io.h"
#include "test_util.h"

// The scans' point type (x y z intensity float32, ring uint16, timestamp float64), registered with PCL so
// its reader fills every field.
struct EIGEN_ALIGN16 PointXYZIRT {
  PCL_ADD_POINT4D;
  float intensity;
  std::uint16_t ring;
  double timestamp;
  PCL_MAKE_ALIGNED_OPERATOR_NEW
};

POINT_CLOUD_REGISTER_POINT_STRUCT(PointXYZIRT, (float, x, x)(float, y, y)(float, z, z)(float, intensity, intensity)(
                                                   std::uint16_t, ring, ring)(double, timestamp, timestamp))

namespace vilslam {
namespace {

void expect_same_cloud(const pcl::PointCloud<PointXYZIRT>& theirs, const PointCloud& ours) {
  ASSERT_EQ(ours.size(), theirs.size());
  ASSERT_EQ(ours.intensity.size(), theirs.size());
  ASSERT_EQ(ours.ring.size(), theirs.size());
  ASSERT_EQ(ours.time_s.size(), theirs.size());
  for (std::size_t i = 0; i < theirs.size(); ++i) {
    ASSERT_EQ(ours.points[i].x(), theirs[i].x) << i;
    ASSERT_EQ(ours.points[i].y(), theirs[i].y) << i;
    ASSERT_EQ(ours.points[i].z(), theirs[i].z) << i;
    ASSERT_EQ(ours.intensity[i], theirs[i].intensity) << i;
    ASSERT_EQ(ours.ring[i], theirs[i].ring) << i;
    ASSERT_EQ(ours.time_s[i], theirs[i].timestamp) << i;
  }
}

TEST(PclCompressed, RealPjlabScansReadAsPclReadsThem) {
  VILSLAM_REQUIRE_SHARED_DATA(dir, "lidar/pjlab_5scans");
  for (const char* stamp : {"468", "568", "668", "768", "868"}) {
    const std::string path = dir + "/2021-10-26-16-21-29-" + stamp + ".pcd";
    SCOPED_TRACE(path);
    pcl::PointCloud<PointXYZIRT> theirs;
    ASSERT_EQ(pcl::io::loadPCDFile(path, theirs), 0);
    ASSERT_GT(theirs.size(), 80000u);
    expect_same_cloud(theirs, read_cloud(path));
  }
}

// A cloud with the fields in an odd order, a count-3 field, a padding field and narrow types, written
// by PCL's binary_compressed writer (its LZF compressor finds real back references in it).
TEST(PclCompressed, WeReadWhatPclCompresses) {
  constexpr std::size_t n = 5000;
  struct FieldSpec {
    const char* name;
    std::uint8_t datatype;
    std::uint32_t count, bytes;
  };
  const FieldSpec specs[] = {{"timestamp", pcl::PCLPointField::FLOAT64, 1, 8}, {"ring", pcl::PCLPointField::UINT16, 1, 2},
                             {"normal", pcl::PCLPointField::FLOAT32, 3, 12},   {"z", pcl::PCLPointField::FLOAT32, 1, 4},
                             {"_", pcl::PCLPointField::UINT8, 2, 2},           {"x", pcl::PCLPointField::FLOAT32, 1, 4},
                             {"intensity", pcl::PCLPointField::UINT8, 1, 1},   {"y", pcl::PCLPointField::FLOAT32, 1, 4}};
  pcl::PCLPointCloud2 cloud;
  for (const FieldSpec& f : specs) {
    pcl::PCLPointField field;
    field.name = f.name;
    field.offset = cloud.point_step;
    field.datatype = f.datatype;
    field.count = f.count;
    cloud.fields.push_back(field);
    cloud.point_step += f.bytes;
  }
  cloud.width = n;
  cloud.height = 1;
  cloud.row_step = cloud.point_step * n;
  cloud.is_dense = true;
  cloud.data.resize(cloud.row_step);
  const auto put = [&](std::size_t i, std::size_t field, const void* v, std::size_t bytes) {
    std::memcpy(cloud.data.data() + i * cloud.point_step + cloud.fields[field].offset, v, bytes);
  };
  for (std::size_t i = 0; i < n; ++i) {
    const double t = 1635236489.468 + 2e-5 * i;
    const std::uint16_t ring = static_cast<std::uint16_t>(i % 32);
    const float normal[3] = {0.0f, 0.0f, 1.0f}, z = 0.5f * (i % 7), x = 0.01f * i, y = -3.0f;
    const std::uint8_t pad[2] = {0, 0}, intensity = static_cast<std::uint8_t>(i % 200);
    put(i, 0, &t, 8);
    put(i, 1, &ring, 2);
    put(i, 2, normal, 12);
    put(i, 3, &z, 4);
    put(i, 4, pad, 2);
    put(i, 5, &x, 4);
    put(i, 6, &intensity, 1);
    put(i, 7, &y, 4);
  }
  const std::string path = (test::temp_dir() / "pcl_compressed.pcd").string();
  ASSERT_EQ(pcl::PCDWriter().writeBinaryCompressed(path, cloud), 0);
  ASSERT_NE(test::read_file_bytes(path).find("DATA binary_compressed"), std::string::npos);
  const PointCloud ours = read_cloud(path);
  ASSERT_EQ(ours.size(), n);
  for (std::size_t i = 0; i < n; ++i) {
    ASSERT_EQ(ours.points[i], Eigen::Vector3f(0.01f * i, -3.0f, 0.5f * (i % 7))) << i;
    ASSERT_EQ(ours.intensity[i], static_cast<float>(i % 200)) << i;
    ASSERT_EQ(ours.ring[i], i % 32) << i;
    ASSERT_EQ(ours.time_s[i], 1635236489.468 + 2e-5 * i) << i;
  }
}

}  // namespace
}  // namespace vilslam
