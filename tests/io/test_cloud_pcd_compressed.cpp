// PCD DATA binary_compressed (PCL's LZF layout) with any field layout, corrupt files, and the five real
// scans of ../shared/data/lidar/pjlab_5scans (PCL's own reader is compared in tests/pcl_interop).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <set>

#include "common/error.h"
#include "io/cloud_io.h"
#include "io/scan_file.h"
#include "test_util.h"

namespace vilslam {
namespace {

namespace fs = std::filesystem;

// One PCD field: name, TYPE, SIZE, COUNT, and the bytes of every point (size * count each).
struct Field {
  std::string name;
  char type;
  std::size_t size, count;
  std::string values;
};

template <typename T>
void append(std::string& s, T v) {
  s.append(reinterpret_cast<const char*>(&v), sizeof v);
}

// LZF with literal runs only (a valid stream for any data): control byte n - 1, then n <= 32 bytes.
std::string lzf_literals(const std::string& data) {
  std::string out;
  for (std::size_t at = 0; at < data.size(); at += 32) {
    const std::size_t n = std::min<std::size_t>(32, data.size() - at);
    out.push_back(static_cast<char>(n - 1));
    out += data.substr(at, n);
  }
  return out;
}

// A binary_compressed PCD as PCL lays it out: the fields one after another, LZF-compressed, behind the
// compressed and uncompressed sizes.
std::string compressed_pcd(const std::vector<Field>& fields, std::size_t points) {
  std::string header = "# .PCD v0.7\nVERSION 0.7\nFIELDS", sizes = "SIZE", types = "TYPE", counts = "COUNT", by_field;
  for (const Field& f : fields) {
    header += " " + f.name;
    sizes += " " + std::to_string(f.size);
    types += std::string(" ") + f.type;
    counts += " " + std::to_string(f.count);
    by_field += f.values;
  }
  const std::string n = std::to_string(points);
  std::string out = header + "\n" + sizes + "\n" + types + "\n" + counts + "\nWIDTH " + n +
                    "\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS " + n + "\nDATA binary_compressed\n";
  const std::string lzf = lzf_literals(by_field);
  append<std::uint32_t>(out, static_cast<std::uint32_t>(lzf.size()));
  append<std::uint32_t>(out, static_cast<std::uint32_t>(by_field.size()));
  return out + lzf;
}

void write_bytes(const fs::path& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary) << bytes;
}

constexpr std::size_t kPoints = 300;

// Timestamp first, x/y/z apart, a padding field, a count-3 field, uint8 intensity, uint16 ring.
std::vector<Field> odd_layout() {
  std::vector<Field> f = {{"timestamp", 'F', 8, 1, {}}, {"y", 'F', 4, 1, {}},      {"_", 'U', 1, 3, {}},
                          {"normal", 'F', 4, 3, {}},    {"x", 'F', 4, 1, {}},      {"ring", 'U', 2, 1, {}},
                          {"z", 'F', 4, 1, {}},         {"intensity", 'U', 1, 1, {}}};
  for (std::size_t i = 0; i < kPoints; ++i) {
    append<double>(f[0].values, 1635236489.468 + 1e-5 * i);
    append<float>(f[1].values, -0.5f * i);
    f[2].values += std::string(3, '\x7f');
    for (int k = 0; k < 3; ++k) append<float>(f[3].values, 9.0f);
    append<float>(f[4].values, 0.25f * i);
    append<std::uint16_t>(f[5].values, static_cast<std::uint16_t>(i % 128));
    append<float>(f[6].values, 1.0f + i);
    append<std::uint8_t>(f[7].values, static_cast<std::uint8_t>(i % 256));
  }
  return f;
}

TEST(PcdCompressed, ReadsAnyFieldLayout) {
  const fs::path path = test::temp_dir() / "odd.pcd";
  write_bytes(path, compressed_pcd(odd_layout(), kPoints));
  const PointCloud cloud = read_cloud(path.string());
  ASSERT_EQ(cloud.size(), kPoints);
  ASSERT_EQ(cloud.intensity.size(), kPoints);
  ASSERT_EQ(cloud.ring.size(), kPoints);
  ASSERT_EQ(cloud.time_s.size(), kPoints);
  for (std::size_t i = 0; i < kPoints; ++i) {
    ASSERT_EQ(cloud.points[i], Eigen::Vector3f(0.25f * i, -0.5f * i, 1.0f + i)) << i;
    ASSERT_EQ(cloud.intensity[i], static_cast<float>(i % 256)) << i;
    ASSERT_EQ(cloud.ring[i], i % 128) << i;
    ASSERT_EQ(cloud.time_s[i], 1635236489.468 + 1e-5 * i) << i;
  }
  // The sweep keeps ring and time: offsets from the earliest point, which starts the sweep.
  const LidarScan scan = scan_from_cloud(cloud);
  EXPECT_TRUE(scan.has_ring);
  EXPECT_EQ(scan.t_ns, 1635236489'468000000);
  EXPECT_EQ(scan.points[7].ring, 7);
  EXPECT_NEAR(scan.points[kPoints - 1].t_offset_s, 1e-5 * (kPoints - 1), 1e-7);
}

std::string error_of(const fs::path& path) {
  try {
    read_cloud(path.string());
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), path.string());
    return e.what();
  }
  ADD_FAILURE() << "no InputError for " << path;
  return "";
}

TEST(PcdCompressed, CorruptOrTruncatedPayloadIsAnInputError) {
  const fs::path dir = test::temp_dir();
  const std::string good = compressed_pcd(odd_layout(), kPoints);
  const std::size_t payload = good.find("DATA binary_compressed\n") + 23;
  // Every truncation inside the payload.
  for (std::size_t size = payload; size < good.size(); size += 97) {
    write_bytes(dir / "t.pcd", good.substr(0, size));
    EXPECT_NE(error_of(dir / "t.pcd").find("binary_compressed payload"), std::string::npos) << size;
  }
  // Uncompressed size not matching the header's points and fields.
  std::string wrong = good;
  const std::uint32_t more = static_cast<std::uint32_t>(kPoints * 38 + 1);  // 38 bytes a point
  std::memcpy(wrong.data() + payload + 4, &more, 4);
  write_bytes(dir / "w.pcd", wrong);
  EXPECT_NE(error_of(dir / "w.pcd").find("does not match 300 points of 38 bytes"), std::string::npos);
  // A back reference before the start of the output (the first chunk turned into one).
  std::string ref = good;
  ref[payload + 8] = static_cast<char>(0x20);
  write_bytes(dir / "r.pcd", ref);
  EXPECT_NE(error_of(dir / "r.pcd").find("before the start of the output"), std::string::npos);
  // A field too wide to be a point field.
  write_bytes(dir / "wide.pcd", "FIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 18446744073709551615\nPOINTS 1\n"
                                "DATA binary_compressed\n");
  EXPECT_NE(error_of(dir / "wide.pcd").find("bad header: field 'z' has SIZE 4 COUNT"), std::string::npos);
  // A ring that is not an integer in 0..65535 (a float field named ring).
  std::vector<Field> fields = {{"x", 'F', 4, 1, {}}, {"y", 'F', 4, 1, {}}, {"z", 'F', 4, 1, {}}, {"ring", 'F', 4, 1, {}}};
  for (Field& f : fields) append<float>(f.values, f.name == "ring" ? -1.0f : 0.0f);
  write_bytes(dir / "ring.pcd", compressed_pcd(fields, 1));
  EXPECT_NE(error_of(dir / "ring.pcd").find("point 0: ring"), std::string::npos);
}

TEST(PcdCompressed, ReadsTheRealPjlabScansWithRingAndTime) {
  VILSLAM_REQUIRE_SHARED_DATA(dir, "lidar/pjlab_5scans");
  for (const char* stamp : {"468", "568", "668", "768", "868"}) {
    const std::string path = dir + "/2021-10-26-16-21-29-" + stamp + ".pcd";
    SCOPED_TRACE(path);
    const PointCloud cloud = read_cloud(path);
    ASSERT_GT(cloud.size(), 80000u);
    ASSERT_EQ(cloud.ring.size(), cloud.size());
    ASSERT_EQ(cloud.time_s.size(), cloud.size());
    const auto [t_min, t_max] = std::minmax_element(cloud.time_s.begin(), cloud.time_s.end());
    EXPECT_GT(*t_max - *t_min, 0.05);  // one 10 Hz sweep
    EXPECT_LT(*t_max - *t_min, 0.11);
    const LidarScan scan = scan_from_cloud(cloud);
    EXPECT_TRUE(scan.has_ring);
    const std::set<std::uint16_t> rings(cloud.ring.begin(), cloud.ring.end());
    EXPECT_GE(rings.size(), 32u);  // a multi-beam spinning sensor (rings 0..60 in these scans)
    EXPECT_LE(*rings.rbegin(), 127);
  }
}

}  // namespace
}  // namespace vilslam
