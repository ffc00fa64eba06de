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

namespace cloud_detail {

std::size_t scalar_size(Scalar type) {
  switch (type) {
    case Scalar::kI8:
    case Scalar::kU8:
      return 1;
    case Scalar::kI16:
    case Scalar::kU16:
      return 2;
    case Scalar::kI32:
    case Scalar::kU32:
    case Scalar::kF32:
      return 4;
    case Scalar::kF64:
      return 8;
  }
  return 0;
}

namespace {

template <typename T>
double load_as(const char* p) {
  T v;
  std::memcpy(&v, p, sizeof(T));
  return static_cast<double>(v);
}

}  // namespace

double load_scalar(const char* p, Scalar type) {
  switch (type) {
    case Scalar::kI8:
      return load_as<std::int8_t>(p);
    case Scalar::kU8:
      return load_as<std::uint8_t>(p);
    case Scalar::kI16:
      return load_as<std::int16_t>(p);
    case Scalar::kU16:
      return load_as<std::uint16_t>(p);
    case Scalar::kI32:
      return load_as<std::int32_t>(p);
    case Scalar::kU32:
      return load_as<std::uint32_t>(p);
    case Scalar::kF32:
      return load_as<float>(p);
    case Scalar::kF64:
      return load_as<double>(p);
  }
  return 0.0;
}

std::vector<std::string> split_words(const std::string& line) {
  std::istringstream in(line);
  std::vector<std::string> words;
  for (std::string w; in >> w;) words.push_back(w);
  return words;
}

PointCloud decode_binary(const std::string& path, const std::string& bytes, std::size_t begin, std::size_t count,
                         const RecordLayout& layout) {
  if (begin > bytes.size() || (bytes.size() - begin) / layout.stride < count) {
    throw InputError(path, "truncated payload: header declares " + std::to_string(count) + " points of " +
                               std::to_string(layout.stride) + " bytes, file has " +
                               std::to_string(bytes.size() - std::min(begin, bytes.size())) + " bytes of data");
  }
  PointCloud cloud;
  cloud.points.resize(count);
  if (layout.has_intensity) cloud.intensity.resize(count);
  for (std::size_t i = 0; i < count; ++i) {
    const char* record = bytes.data() + begin + i * layout.stride;
    for (int k = 0; k < 3; ++k) {
      cloud.points[i][k] = static_cast<float>(load_scalar(record + layout.offset[k], layout.type[k]));
    }
    if (layout.has_intensity) {
      cloud.intensity[i] = static_cast<float>(load_scalar(record + layout.offset[3], layout.type[3]));
    }
  }
  return cloud;
}

PointCloud decode_ascii(const std::string& path, const std::string& bytes, std::size_t begin, std::size_t count,
                        const RecordLayout& layout, long first_line) {
  PointCloud cloud;
  cloud.points.resize(count);
  if (layout.has_intensity) cloud.intensity.resize(count);
  std::size_t pos = begin;
  std::vector<double> values(layout.stride);
  for (std::size_t i = 0; i < count; ++i) {
    const long line_no = first_line + static_cast<long>(i);
    if (pos >= bytes.size()) {
      throw InputError(path, "truncated payload: expected " + std::to_string(count) + " points, found " +
                                 std::to_string(i), line_no);
    }
    std::size_t end = bytes.find('\n', pos);
    if (end == std::string::npos) end = bytes.size();
    const std::vector<std::string> words = split_words(bytes.substr(pos, end - pos));
    pos = end + 1;
    if (words.size() < layout.stride) {
      throw InputError(path, "expected " + std::to_string(layout.stride) + " values, found " +
                                 std::to_string(words.size()), line_no);
    }
    const auto value = [&](std::size_t token) {
      char* stop = nullptr;
      const double v = std::strtod(words[token].c_str(), &stop);
      if (stop == words[token].c_str() || *stop != '\0') {
        throw InputError(path, "not a number: '" + words[token] + "'", line_no);
      }
      return v;
    };
    for (int k = 0; k < 3; ++k) cloud.points[i][k] = static_cast<float>(value(layout.offset[k]));
    if (layout.has_intensity) cloud.intensity[i] = static_cast<float>(value(layout.offset[3]));
  }
  return cloud;
}

std::string pack_xyzi(const PointCloud& cloud) {
  std::string out(cloud.size() * 4 * sizeof(float), '\0');
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    const float record[4] = {cloud.points[i].x(), cloud.points[i].y(), cloud.points[i].z(),
                             cloud.intensity.empty() ? 0.0f : cloud.intensity[i]};
    std::memcpy(out.data() + i * sizeof record, record, sizeof record);
  }
  return out;
}

}  // namespace cloud_detail

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
  layout.stride = kStride;
  for (std::size_t k = 0; k < 4; ++k) layout.offset[k] = k * sizeof(float);
  layout.has_intensity = true;
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
