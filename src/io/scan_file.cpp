#include "io/scan_file.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <vector>

#include "common/error.h"
#include "io/cloud_io.h"

namespace vilslam {
namespace {

constexpr char kMagic[8] = {'V', 'L', 'S', 'C', 'A', 'N', '0', '1'};
constexpr std::uint32_t kFlagHasRing = 1;

static_assert(sizeof(float) == 4, "float32 expected");

// The formats are little-endian; so is every platform this builds on (checked at compile time).
static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__, "little-endian host expected");

std::vector<char> read_all(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  if (!f) throw InputError(path, "cannot open scan file");
  std::vector<char> bytes((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
  if (f.bad()) throw InputError(path, "read error");
  return bytes;
}

template <typename T>
T load(const char* p) {
  T v;
  std::memcpy(&v, p, sizeof v);
  return v;
}

template <typename T>
void store(std::ofstream& f, T v) {
  f.write(reinterpret_cast<const char*>(&v), sizeof v);
}

// Validates the header of a project scan held in `size` bytes starting at `data`; returns num_points.
std::size_t parse_header(const char* data, std::size_t size, const std::string& path) {
  if (size < kScanHeaderBytes) throw InputError(path, "truncated scan header (" + std::to_string(size) + " bytes)");
  if (std::memcmp(data, kMagic, sizeof kMagic) != 0) throw InputError(path, "wrong magic (expected VLSCAN01)");
  const std::size_t n = load<std::uint32_t>(data + 8);
  const std::size_t expected = kScanHeaderBytes + n * kScanPointBytes;
  if (size != expected) {
    throw InputError(path, "file has " + std::to_string(size) + " bytes, header promises " + std::to_string(n) +
                               " points (" + std::to_string(expected) + " bytes)");
  }
  return n;
}

std::size_t file_size(const std::string& path) {
  std::error_code ec;
  const auto size = std::filesystem::file_size(path, ec);
  if (ec) throw InputError(path, "cannot open scan file");
  return size;
}

}  // namespace

LidarScan read_scan_file(const std::string& path) {
  const std::vector<char> bytes = read_all(path);
  const std::size_t n = parse_header(bytes.data(), bytes.size(), path);
  LidarScan scan;
  scan.has_ring = (load<std::uint32_t>(bytes.data() + 12) & kFlagHasRing) != 0;
  scan.points.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const char* p = bytes.data() + kScanHeaderBytes + i * kScanPointBytes;
    LidarPoint& q = scan.points[i];
    q.x = load<float>(p);
    q.y = load<float>(p + 4);
    q.z = load<float>(p + 8);
    q.intensity = load<float>(p + 12);
    q.t_offset_s = load<float>(p + 16);
    q.ring = load<std::uint16_t>(p + 20);
    if (!std::isfinite(q.x) || !std::isfinite(q.y) || !std::isfinite(q.z) || !std::isfinite(q.intensity) ||
        !std::isfinite(q.t_offset_s)) {
      throw InputError(path, "point " + std::to_string(i) + " has a non-finite value");
    }
  }
  return scan;
}

void write_scan_file(const std::string& path, const LidarScan& scan) {
  std::ofstream f(path, std::ios::binary | std::ios::trunc);
  f.write(kMagic, sizeof kMagic);
  store<std::uint32_t>(f, static_cast<std::uint32_t>(scan.points.size()));
  store<std::uint32_t>(f, scan.has_ring ? kFlagHasRing : 0u);
  for (const LidarPoint& p : scan.points) {
    for (float v : {p.x, p.y, p.z, p.intensity, p.t_offset_s}) store<float>(f, v);
    store<std::uint16_t>(f, p.ring);
    store<std::uint16_t>(f, 0);
  }
  f.flush();
  if (!f) throw std::runtime_error("cannot write " + path);
}

std::size_t check_scan_file(const std::string& path) {
  const std::size_t size = file_size(path);
  std::ifstream f(path, std::ios::binary);
  char header[kScanHeaderBytes] = {};
  f.read(header, sizeof header);
  return parse_header(header, f ? size : static_cast<std::size_t>(f.gcount()), path);
}

LidarScan read_kitti_scan(const std::string& path) { return scan_from_cloud(read_cloud(path)); }

LidarScan scan_from_cloud(const PointCloud& cloud, TimeNs t_ns) {
  LidarScan scan;
  scan.has_ring = !cloud.ring.empty();
  double t0_s = 0.0;  // the earliest point time, the scan's start
  if (!cloud.time_s.empty()) {
    t0_s = *std::min_element(cloud.time_s.begin(), cloud.time_s.end());
    if (t_ns == 0) t_ns = static_cast<TimeNs>(std::llround(t0_s * 1e9));
  }
  scan.t_ns = t_ns;
  scan.points.resize(cloud.size());
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    LidarPoint& q = scan.points[i];
    q.x = cloud.points[i].x();
    q.y = cloud.points[i].y();
    q.z = cloud.points[i].z();
    q.intensity = cloud.intensity.empty() ? 0.0f : cloud.intensity[i];
    if (scan.has_ring) q.ring = cloud.ring[i];
    if (!cloud.time_s.empty()) q.t_offset_s = static_cast<float>(cloud.time_s[i] - t0_s);
  }
  return scan;
}

std::size_t check_kitti_scan(const std::string& path) {
  const std::size_t size = file_size(path);
  if (size % 16 != 0) throw InputError(path, "size " + std::to_string(size) + " is not a multiple of 16 bytes");
  return size / 16;
}

}  // namespace vilslam
