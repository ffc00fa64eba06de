// The record level shared by the PLY and PCD codecs: scalar types, field layouts, and decoding packed
// binary or ASCII records into a PointCloud (x y z and the optional intensity, ring and time).
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <sstream>

#include "common/error.h"
#include "io/cloud_formats.h"

namespace vilslam::cloud_detail {

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

// A cloud of `count` points with the optional per-point vectors the layout has.
PointCloud empty_cloud(const RecordLayout& layout, std::size_t count) {
  PointCloud cloud;
  cloud.points.resize(count);
  if (layout.has[kIntensity]) cloud.intensity.resize(count);
  if (layout.has[kRing]) cloud.ring.resize(count);
  if (layout.has[kTime]) cloud.time_s.resize(count);
  return cloud;
}

// Stores field `slot` of point i; a ring must be an integer in 0..65535, a time finite.
void store(const std::string& path, PointCloud& cloud, int slot, std::size_t i, double v) {
  switch (slot) {
    case kX:
    case kY:
    case kZ:
      cloud.points[i][slot] = static_cast<float>(v);
      return;
    case kIntensity:
      cloud.intensity[i] = static_cast<float>(v);
      return;
    case kRing:
      if (!(v >= 0.0 && v <= 65535.0) || v != std::floor(v)) {
        throw InputError(path, "point " + std::to_string(i) + ": ring " + std::to_string(v) +
                                   " is not an integer in 0..65535");
      }
      cloud.ring[i] = static_cast<std::uint16_t>(v);
      return;
    case kTime:
      if (!std::isfinite(v)) throw InputError(path, "point " + std::to_string(i) + " has a non-finite time");
      cloud.time_s[i] = v;
      return;
  }
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

int field_slot(const std::string& name) {
  if (name == "x") return kX;
  if (name == "y") return kY;
  if (name == "z") return kZ;
  if (name == "intensity" || name == "scalar_intensity" || name == "scalar_Intensity") return kIntensity;
  if (name == "ring") return kRing;
  if (name == "timestamp" || name == "time") return kTime;
  return -1;
}

void RecordLayout::add_field(const std::string& name, Scalar field_type, std::size_t width) {
  const int slot = field_slot(name);
  if (slot >= 0 && !has[slot]) {
    has[slot] = true;
    offset[slot] = stride;
    type[slot] = field_type;
  }
  stride += width;
}

PointCloud decode_binary(const std::string& path, const std::string& bytes, std::size_t begin, std::size_t count,
                         const RecordLayout& layout) {
  if (begin > bytes.size() || (bytes.size() - begin) / layout.stride < count) {
    throw InputError(path, "truncated payload: header declares " + std::to_string(count) + " points of " +
                               std::to_string(layout.stride) + " bytes, file has " +
                               std::to_string(bytes.size() - std::min(begin, bytes.size())) + " bytes of data");
  }
  PointCloud cloud = empty_cloud(layout, count);
  for (std::size_t i = 0; i < count; ++i) {
    const char* record = bytes.data() + begin + i * layout.stride;
    for (int slot = 0; slot < kNumSlots; ++slot) {
      if (layout.has[slot]) store(path, cloud, slot, i, load_scalar(record + layout.offset[slot], layout.type[slot]));
    }
  }
  return cloud;
}

PointCloud decode_ascii(const std::string& path, const std::string& bytes, std::size_t begin, std::size_t count,
                        const RecordLayout& layout, long first_line) {
  // Every record takes a byte at least: a count the file cannot hold is refused before allocating for it.
  if (begin > bytes.size() || count > bytes.size() - begin) {
    throw InputError(path, "truncated payload: header declares " + std::to_string(count) + " points, file has " +
                               std::to_string(bytes.size() - std::min(begin, bytes.size())) + " bytes of data",
                     first_line);
  }
  PointCloud cloud = empty_cloud(layout, count);
  std::size_t pos = begin;
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
    for (int slot = 0; slot < kNumSlots; ++slot) {
      if (!layout.has[slot]) continue;
      const std::string& word = words[layout.offset[slot]];
      char* stop = nullptr;
      const double v = std::strtod(word.c_str(), &stop);
      if (stop == word.c_str() || *stop != '\0') throw InputError(path, "not a number: '" + word + "'", line_no);
      store(path, cloud, slot, i, v);
    }
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

}  // namespace vilslam::cloud_detail
