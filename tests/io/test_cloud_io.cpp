#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>

#include "common/error.h"
#include "io/cloud_io.h"
#include "test_util.h"

namespace vilslam {
namespace {

namespace fs = std::filesystem;

PointCloud random_cloud(std::size_t n, bool with_intensity, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> coord(-80.0f, 80.0f);
  PointCloud cloud;
  for (std::size_t i = 0; i < n; ++i) {
    cloud.points.emplace_back(coord(rng), coord(rng), coord(rng));
    if (with_intensity) cloud.intensity.push_back(std::abs(coord(rng)));
  }
  // Values whose bits a lossy writer would change.
  cloud.points[0] = Eigen::Vector3f(-0.0f, std::numeric_limits<float>::denorm_min(), 1e-30f);
  cloud.points[1] = Eigen::Vector3f(std::numeric_limits<float>::max(), std::numeric_limits<float>::lowest(), 0.1f);
  return cloud;
}

bool same_bits(float a, float b) { return std::memcmp(&a, &b, sizeof a) == 0; }

void expect_bit_identical(const PointCloud& written, const PointCloud& read) {
  ASSERT_EQ(read.size(), written.size());
  ASSERT_EQ(read.intensity.size(), written.size());
  for (std::size_t i = 0; i < written.size(); ++i) {
    for (int k = 0; k < 3; ++k) ASSERT_TRUE(same_bits(read.points[i][k], written.points[i][k])) << i << "," << k;
    const float expected_intensity = written.intensity.empty() ? 0.0f : written.intensity[i];
    ASSERT_TRUE(same_bits(read.intensity[i], expected_intensity)) << i;
  }
}

std::string error_of(const std::string& path) {
  try {
    read_cloud(path);
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), path);
    return e.what();
  }
  ADD_FAILURE() << "no InputError for " << path;
  return "";
}

TEST(CloudIo, RoundTripsEveryWriterBitForBit) {
  const fs::path dir = test::temp_dir();
  for (const char* ext : {".ply", ".pcd"}) {
    for (bool with_intensity : {true, false}) {
      const PointCloud cloud = random_cloud(1000, with_intensity, 7);
      const std::string path = (dir / (std::string("cloud") + (with_intensity ? "_i" : "") + ext)).string();
      write_cloud(path, cloud);
      SCOPED_TRACE(path);
      expect_bit_identical(cloud, read_cloud(path));
    }
  }
}

TEST(CloudIo, WriteLeavesNoTemporaryAndFailsCleanly) {
  const fs::path dir = test::temp_dir();
  write_cloud((dir / "a.pcd").string(), random_cloud(10, true, 1));
  std::size_t files = 0;
  for (const auto& entry : fs::directory_iterator(dir)) files += entry.is_regular_file();
  EXPECT_EQ(files, 1u);
  EXPECT_THROW(write_cloud((dir / "missing_folder" / "a.ply").string(), random_cloud(10, true, 1)), InputError);
  EXPECT_THROW(write_cloud((dir / "a.xyz").string(), random_cloud(10, true, 1)), InputError);
  PointCloud bad = random_cloud(10, true, 1);
  bad.points[3].y() = std::numeric_limits<float>::quiet_NaN();
  EXPECT_THROW(write_cloud((dir / "bad.ply").string(), bad), InputError);
  EXPECT_FALSE(fs::exists(dir / "bad.ply"));
}

TEST(CloudIo, ReadsKittiBin) {
  const fs::path path = test::temp_dir() / "000000.bin";
  const float records[2][4] = {{1.5f, -2.0f, 0.25f, 0.75f}, {10.0f, 20.0f, -3.0f, 0.0f}};
  std::ofstream(path, std::ios::binary).write(reinterpret_cast<const char*>(records), sizeof records);
  const PointCloud cloud = read_cloud(path.string());
  ASSERT_EQ(cloud.size(), 2u);
  EXPECT_EQ(cloud.points[1], Eigen::Vector3f(10.0f, 20.0f, -3.0f));
  EXPECT_EQ(cloud.intensity[0], 0.75f);
}

TEST(CloudIo, ReadsAsciiPlySkippingOtherProperties) {
  const fs::path path = test::temp_dir() / "a.ply";
  test::write_file_bytes(path,
             "ply\nformat ascii 1.0\ncomment test\nelement vertex 2\nproperty uchar red\nproperty double x\n"
             "property float y\nproperty float z\nproperty float intensity\nelement face 1\n"
             "property list uchar int vertex_indices\nend_header\n7 1.5 2 3 9\n8 -1 -2 -3.5 4\n3 0 1 1\n");
  const PointCloud cloud = read_cloud(path.string());
  ASSERT_EQ(cloud.size(), 2u);
  EXPECT_EQ(cloud.points[0], Eigen::Vector3f(1.5f, 2.0f, 3.0f));
  EXPECT_EQ(cloud.points[1], Eigen::Vector3f(-1.0f, -2.0f, -3.5f));
  EXPECT_EQ(cloud.intensity[1], 4.0f);
}

TEST(CloudIo, ReadsBinaryPlyWithMixedTypesAndPrecedingElement) {
  const fs::path path = test::temp_dir() / "b.ply";
  std::string bytes =
      "ply\nformat binary_little_endian 1.0\nelement camera 1\nproperty list uchar float view\n"
      "element vertex 1\nproperty short s\nproperty double x\nproperty float y\nproperty uchar u\n"
      "property float z\nend_header\n";
  const auto append = [&bytes](const auto& v) { bytes.append(reinterpret_cast<const char*>(&v), sizeof v); };
  append(std::uint8_t{2});
  append(1.0f);
  append(2.0f);
  append(std::int16_t{-5});
  append(4.25);
  append(-1.0f);
  append(std::uint8_t{200});
  append(8.0f);
  test::write_file_bytes(path, bytes);
  const PointCloud cloud = read_cloud(path.string());
  ASSERT_EQ(cloud.size(), 1u);
  EXPECT_EQ(cloud.points[0], Eigen::Vector3f(4.25f, -1.0f, 8.0f));
  EXPECT_TRUE(cloud.intensity.empty());
}

TEST(CloudIo, ReadsAsciiPcdSkippingOtherFields) {
  const fs::path path = test::temp_dir() / "a.pcd";
  test::write_file_bytes(path,
             "# comment\nVERSION 0.7\nFIELDS x y z rgb normal intensity\nSIZE 4 4 4 4 4 2\nTYPE F F F U F U\n"
             "COUNT 1 1 1 1 3 1\nWIDTH 2\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS 2\nDATA ascii\n"
             "1 2 3 255 0 0 1 17\n-4 5.5 6 0 1 0 0 3\n");
  const PointCloud cloud = read_cloud(path.string());
  ASSERT_EQ(cloud.size(), 2u);
  EXPECT_EQ(cloud.points[1], Eigen::Vector3f(-4.0f, 5.5f, 6.0f));
  EXPECT_EQ(cloud.intensity[0], 17.0f);
}

TEST(CloudIo, BadInputsThrowInputErrorNamingTheFile) {
  const fs::path dir = test::temp_dir();
  EXPECT_NE(error_of((dir / "absent.pcd").string()).find("does not exist"), std::string::npos);
  test::write_file_bytes(dir / "x.las", "abc");
  EXPECT_NE(error_of((dir / "x.las").string()).find("extension"), std::string::npos);
  test::write_file_bytes(dir / "h.ply", "plx\nformat ascii 1.0\nend_header\n");
  EXPECT_NE(error_of((dir / "h.ply").string()).find("bad header"), std::string::npos);
  test::write_file_bytes(dir / "be.ply", "ply\nformat binary_big_endian 1.0\nelement vertex 0\nend_header\n");
  EXPECT_NE(error_of((dir / "be.ply").string()).find("binary_big_endian"), std::string::npos);
  test::write_file_bytes(dir / "nodata.pcd", "FIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nPOINTS 1\n");
  EXPECT_NE(error_of((dir / "nodata.pcd").string()).find("bad header"), std::string::npos);
  test::write_file_bytes(dir / "c.pcd", "FIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nPOINTS 1\nDATA binary_compressed\n");
  EXPECT_NE(error_of((dir / "c.pcd").string()).find("no size header"), std::string::npos);
  test::write_file_bytes(dir / "t.bin", std::string(20, '\0'));
  EXPECT_NE(error_of((dir / "t.bin").string()).find("truncated"), std::string::npos);
  test::write_file_bytes(dir / "word.pcd", "FIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nPOINTS 1\nDATA ascii\n1 two 3\n");
  EXPECT_NE(error_of((dir / "word.pcd").string()).find("word.pcd:6: not a number"), std::string::npos);
  test::write_file_bytes(dir / "nan.pcd", "FIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nPOINTS 2\nDATA ascii\n1 2 3\nnan 0 0\n");
  EXPECT_NE(error_of((dir / "nan.pcd").string()).find("point 1 has a non-finite"), std::string::npos);

  const std::string good_ply = (dir / "good.ply").string();
  const std::string good_pcd = (dir / "good.pcd").string();
  write_cloud(good_ply, random_cloud(100, true, 3));
  write_cloud(good_pcd, random_cloud(100, true, 3));
  for (const std::string& good : {good_ply, good_pcd}) {
    const auto size = fs::file_size(good);
    fs::resize_file(good, size - 5);
    EXPECT_NE(error_of(good).find("truncated payload"), std::string::npos) << good;
  }
}

TEST(CloudIo, ReadsSharedRealScansInBothEncodings) {
  VILSLAM_REQUIRE_SHARED_DATA(lidar, "lidar");
  const PointCloud target_pcd = read_cloud(lidar + "/fast_gicp/251370668.pcd");
  const PointCloud source_pcd = read_cloud(lidar + "/fast_gicp/251371071.pcd");
  const PointCloud target_ply = read_cloud(lidar + "/small_gicp/target.ply");
  const PointCloud source_ply = read_cloud(lidar + "/small_gicp/source.ply");
  EXPECT_EQ(target_pcd.size(), 69088u);
  EXPECT_EQ(target_ply.size(), 69088u);
  EXPECT_EQ(source_pcd.size(), source_ply.size());
  EXPECT_GT(source_pcd.size(), 60000u);
  EXPECT_EQ(target_pcd.intensity.size(), target_pcd.size());
  EXPECT_EQ(target_ply.intensity.size(), target_ply.size());
  // The two encodings hold the same scan.
  for (std::size_t i = 0; i < target_pcd.size(); i += 997) {
    EXPECT_LT((target_pcd.points[i] - target_ply.points[i]).norm(), 1e-3f) << i;
  }
}

}  // namespace
}  // namespace vilslam
