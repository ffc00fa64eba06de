// sensor_msgs/PointCloud2 to and from LidarScan, for the field layouts of the common LiDAR drivers.
#include <algorithm>
#include <array>
#include <cstring>
#include <cmath>
#include <optional>

#include "io/ros_convert.h"
#include "io/ros_wire.h"

namespace vilslam {
namespace {

// A timestamp field more than this far from the header stamp is not in the unit assumed.
constexpr double kMaxStampDistance_s = 1000;

const RosPointField* find_field(const RosPointCloud2& cloud, const std::string& name) {
  for (const RosPointField& f : cloud.fields) {
    if (f.name == name) return &f;
  }
  return nullptr;
}

// One field's value, stored in the cloud's byte order (is_bigendian), as a double.
double read_value(const std::uint8_t* p, std::uint8_t datatype, bool big_endian) {
  auto get = [p, big_endian](auto value) {
    std::array<std::uint8_t, sizeof value> bytes;
    std::memcpy(bytes.data(), p, sizeof value);
    if (big_endian) std::reverse(bytes.begin(), bytes.end());
    std::memcpy(&value, bytes.data(), sizeof value);
    return static_cast<double>(value);
  };
  switch (static_cast<RosPointType>(datatype)) {
    case RosPointType::kInt8: return get(std::int8_t{});
    case RosPointType::kUint8: return get(std::uint8_t{});
    case RosPointType::kInt16: return get(std::int16_t{});
    case RosPointType::kUint16: return get(std::uint16_t{});
    case RosPointType::kInt32: return get(std::int32_t{});
    case RosPointType::kUint32: return get(std::uint32_t{});
    case RosPointType::kFloat32: return get(float{});
    case RosPointType::kFloat64: return get(double{});
  }
  return 0;
}

// How a field's values become seconds since the header stamp.
enum class TimeUnit { kRelativeSeconds, kRelativeNanoseconds, kAbsolute };

struct TimeField {
  const RosPointField* field = nullptr;
  TimeUnit unit = TimeUnit::kRelativeSeconds;
};

std::optional<TimeField> time_field(const RosPointCloud2& cloud) {
  if (const auto* f = find_field(cloud, "time")) return TimeField{f, TimeUnit::kRelativeSeconds};
  if (const auto* f = find_field(cloud, "t")) return TimeField{f, TimeUnit::kRelativeNanoseconds};
  if (const auto* f = find_field(cloud, "offset_time")) return TimeField{f, TimeUnit::kRelativeNanoseconds};
  if (const auto* f = find_field(cloud, "timestamp")) return TimeField{f, TimeUnit::kAbsolute};
  return std::nullopt;
}

// Checks the geometry of the cloud and of each field against point_step.
void check_layout(const RosPointCloud2& cloud) {
  // An empty cloud is 0 x 0 or 1 x 0 (PCL, the drivers); rows of no points (and no bytes) could number 4e9.
  if (cloud.width == 0 && cloud.height > 1) {
    throw WireError("PointCloud2 of width 0 has " + std::to_string(cloud.height) + " rows");
  }
  if (std::uint64_t{cloud.row_step} < std::uint64_t{cloud.width} * cloud.point_step) {
    throw WireError("PointCloud2 row_step " + std::to_string(cloud.row_step) + " < width x point_step");
  }
  if (cloud.data.size() < std::uint64_t{cloud.row_step} * cloud.height) {
    throw WireError("PointCloud2 data has " + std::to_string(cloud.data.size()) + " bytes, row_step x height is " +
                    std::to_string(std::uint64_t{cloud.row_step} * cloud.height));
  }
  for (const RosPointField& f : cloud.fields) {
    const std::size_t size = ros_point_type_size(f.datatype);
    if (size == 0) throw WireError("PointCloud2 field '" + f.name + "' has unknown datatype " + std::to_string(f.datatype));
    if (std::uint64_t{f.offset} + size > cloud.point_step) {
      throw WireError("PointCloud2 field '" + f.name + "' ends beyond point_step " + std::to_string(cloud.point_step));
    }
  }
  for (const char* axis : {"x", "y", "z"}) {
    if (!find_field(cloud, axis)) throw WireError(std::string("PointCloud2 has no '") + axis + "' field");
  }
}

}  // namespace

std::string point_cloud2_layout(const RosPointCloud2& cloud) {
  if (find_field(cloud, "time")) return "velodyne";
  if (find_field(cloud, "t")) return "ouster";
  if (find_field(cloud, "offset_time")) return "livox";
  if (find_field(cloud, "timestamp")) return find_field(cloud, "ring") ? "hesai" : "livox";
  return "xyz";
}

LidarScan scan_from_point_cloud2(const RosPointCloud2& cloud) {
  check_layout(cloud);
  const RosPointField* fx = find_field(cloud, "x");
  const RosPointField* fy = find_field(cloud, "y");
  const RosPointField* fz = find_field(cloud, "z");
  const RosPointField* fi = find_field(cloud, "intensity");
  const RosPointField* fr = find_field(cloud, "ring");
  const std::optional<TimeField> ft = time_field(cloud);
  const bool big_endian = cloud.is_bigendian != 0;
  const double stamp_s = ns_to_s(cloud.header.stamp_ns);

  // Absolute timestamps: seconds (Hesai) or nanoseconds (livox_ros_driver2), told apart by the stamp.
  double absolute_scale = 1.0;
  std::vector<std::pair<LidarPoint, double>> points;  // point, time since the stamp [s]
  points.reserve(std::size_t{cloud.width} * cloud.height);
  for (std::uint32_t row = 0; row < cloud.height; ++row) {
    for (std::uint32_t col = 0; col < cloud.width; ++col) {
      const std::uint8_t* p = cloud.data.data() + std::size_t{row} * cloud.row_step + std::size_t{col} * cloud.point_step;
      LidarPoint point;
      point.x = static_cast<float>(read_value(p + fx->offset, fx->datatype, big_endian));
      point.y = static_cast<float>(read_value(p + fy->offset, fy->datatype, big_endian));
      point.z = static_cast<float>(read_value(p + fz->offset, fz->datatype, big_endian));
      if (!std::isfinite(point.x) || !std::isfinite(point.y) || !std::isfinite(point.z)) continue;
      if (point.x == 0 && point.y == 0 && point.z == 0) continue;
      if (fi) point.intensity = static_cast<float>(read_value(p + fi->offset, fi->datatype, big_endian));
      if (fr) {
        const double ring = read_value(p + fr->offset, fr->datatype, big_endian);
        if (!(ring >= 0 && ring <= 65535) || ring != std::floor(ring)) {
          throw WireError("PointCloud2 'ring' field holds " + std::to_string(ring) + ", not an integer in 0..65535");
        }
        point.ring = static_cast<std::uint16_t>(ring);
      }
      double t_s = 0;
      if (ft) {
        const double v = read_value(p + ft->field->offset, ft->field->datatype, big_endian);
        if (!std::isfinite(v)) throw WireError("PointCloud2 '" + ft->field->name + "' field holds a non-finite value");
        switch (ft->unit) {
          case TimeUnit::kRelativeSeconds: t_s = v; break;
          case TimeUnit::kRelativeNanoseconds: t_s = v * 1e-9; break;
          case TimeUnit::kAbsolute:
            if (points.empty() && std::abs(v - stamp_s) > kMaxStampDistance_s) absolute_scale = 1e-9;
            t_s = v * absolute_scale - stamp_s;
            if (std::abs(t_s) > kMaxStampDistance_s) {
              throw WireError("PointCloud2 'timestamp' " + std::to_string(v) +
                              " is neither seconds nor nanoseconds near the header stamp " + std::to_string(stamp_s));
            }
            break;
        }
      }
      points.emplace_back(point, t_s);
    }
  }

  LidarScan scan;
  scan.has_ring = fr != nullptr;
  double first_s = 0;
  for (const auto& [point, t_s] : points) first_s = std::min(first_s, t_s);
  scan.t_ns = cloud.header.stamp_ns + s_to_ns(first_s);
  const double shift_s = ns_to_s(scan.t_ns - cloud.header.stamp_ns);
  scan.points.reserve(points.size());
  for (auto [point, t_s] : points) {
    point.t_offset_s = static_cast<float>(shift_s == 0 ? t_s : t_s - shift_s);
    scan.points.push_back(point);
  }
  return scan;
}

RosPointCloud2 velodyne_point_cloud2(const LidarScan& scan, const std::string& frame_id) {
  constexpr auto kF32 = static_cast<std::uint8_t>(RosPointType::kFloat32);
  constexpr auto kU16 = static_cast<std::uint8_t>(RosPointType::kUint16);
  RosPointCloud2 m;
  m.header.stamp_ns = scan.t_ns;
  m.header.frame_id = frame_id;
  // A sweep without rings (has_ring false) leaves the ring field out rather than invent zeros.
  m.fields = {{"x", 0, kF32, 1}, {"y", 4, kF32, 1}, {"z", 8, kF32, 1}, {"intensity", 12, kF32, 1}};
  if (scan.has_ring) m.fields.push_back({"ring", 16, kU16, 1});
  m.fields.push_back({"time", scan.has_ring ? 18u : 16u, kF32, 1});
  m.point_step = scan.has_ring ? 22 : 20;
  m.height = 1;
  m.width = static_cast<std::uint32_t>(scan.points.size());
  m.row_step = m.width * m.point_step;
  m.is_dense = 1;
  WireWriter w;
  for (const LidarPoint& p : scan.points) {
    w.write(p.x);
    w.write(p.y);
    w.write(p.z);
    w.write(p.intensity);
    if (scan.has_ring) w.write(p.ring);
    w.write(p.t_offset_s);
  }
  m.data = w.release();
  return m;
}

}  // namespace vilslam
