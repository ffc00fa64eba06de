#include "io/cloud_io.h"

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "common/error.h"
#include "io/cloud_formats.h"

namespace vilslam {

namespace {

std::string extension_of(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, "cannot open file");
  std::ostringstream buffer;
  buffer << in.rdbuf();
  if (in.bad()) throw InputError(path, "read error");
  return buffer.str();
}

// KITTI velodyne .bin: packed float32 records x y z reflectance.
PointCloud decode_kitti_bin(const std::string& path, const std::string& bytes) {
  constexpr std::size_t kStride = 4 * sizeof(float);
  if (bytes.size() % kStride != 0) {
    throw InputError(path, "truncated payload: " + std::to_string(bytes.size()) +
                               " bytes is not a multiple of 16 (x y z reflectance float32)");
  }
  cloud_detail::RecordLayout layout;
  for (const char* name : {"x", "y", "z", "intensity"}) layout.add_field(name, cloud_detail::Scalar::kF32, sizeof(float));
  return cloud_detail::decode_binary(path, bytes, 0, bytes.size() / kStride, layout);
}

void require_finite(const std::string& path, const PointCloud& cloud) {
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    if (!cloud.points[i].allFinite()) {
      throw InputError(path, "point " + std::to_string(i) + " has a non-finite coordinate");
    }
  }
}

}  // namespace

PointCloud read_cloud(const std::string& path) {
  const std::string ext = extension_of(path);
  if (ext != ".ply" && ext != ".pcd" && ext != ".bin") {
    throw InputError(path, "unknown point cloud extension '" + ext + "' (expected .ply, .pcd or .bin)");
  }
  if (!std::filesystem::is_regular_file(path)) throw InputError(path, "file does not exist");
  const std::string bytes = read_file(path);
  PointCloud cloud = ext == ".ply"   ? cloud_detail::decode_ply(path, bytes)
                     : ext == ".pcd" ? cloud_detail::decode_pcd(path, bytes)
                                     : decode_kitti_bin(path, bytes);
  require_finite(path, cloud);
  return cloud;
}

void write_cloud(const std::string& path, const PointCloud& cloud) {
  if (!cloud.intensity.empty() && cloud.intensity.size() != cloud.points.size()) {
    throw std::invalid_argument("write_cloud: intensity must be empty or one per point");
  }
  const std::string ext = extension_of(path);
  if (ext != ".ply" && ext != ".pcd") {
    throw InputError(path, "unknown point cloud extension '" + ext + "' for writing (expected .ply or .pcd)");
  }
  require_finite(path, cloud);
  const std::string bytes = ext == ".ply" ? cloud_detail::encode_ply(cloud) : cloud_detail::encode_pcd(cloud);

  const std::filesystem::path target(path);
  std::filesystem::path temp = target;
  temp += ".tmp" + std::to_string(::getpid());
  {
    std::ofstream out(temp, std::ios::binary | std::ios::trunc);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    out.close();
    if (!out) {
      std::error_code ignored;
      std::filesystem::remove(temp, ignored);
      throw InputError(path, "cannot write file");
    }
  }
  std::error_code ec;
  std::filesystem::rename(temp, target, ec);
  if (ec) {
    std::filesystem::remove(temp, ec);
    throw InputError(path, "cannot rename temporary file into place");
  }
}

}  // namespace vilslam
