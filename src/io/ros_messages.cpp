// Wire (de)serialization of the ROS1 message types in ros_messages.h, field by field in .msg order.
#include "io/ros_messages.h"

#include "io/ros_wire.h"

namespace vilslam {
namespace {

RosHeader read_header(WireReader& r) {
  RosHeader h;
  h.seq = r.read<std::uint32_t>();
  h.stamp_ns = r.time();
  h.frame_id = r.string();
  return h;
}

void write_header(WireWriter& w, const RosHeader& h) {
  w.write(h.seq);
  w.time(h.stamp_ns);
  w.string(h.frame_id);
}

template <std::size_t N>
void read_doubles(WireReader& r, std::array<double, N>& values) {
  for (double& v : values) v = r.read<double>();
}

template <std::size_t N>
void write_doubles(WireWriter& w, const std::array<double, N>& values) {
  for (double v : values) w.write(v);
}

// Runs decode over the whole message and insists that it used every byte.
template <typename Decode>
auto decode_all(const std::vector<std::uint8_t>& bytes, const char* datatype, Decode decode) {
  WireReader r(bytes.data(), bytes.size());
  auto message = decode(r);
  if (r.remaining() != 0) {
    throw WireError(std::to_string(r.remaining()) + " bytes left over after a " + datatype +
                    " (is the message of another type?)");
  }
  return message;
}

}  // namespace

std::size_t ros_point_type_size(std::uint8_t datatype) {
  switch (static_cast<RosPointType>(datatype)) {
    case RosPointType::kInt8:
    case RosPointType::kUint8: return 1;
    case RosPointType::kInt16:
    case RosPointType::kUint16: return 2;
    case RosPointType::kInt32:
    case RosPointType::kUint32:
    case RosPointType::kFloat32: return 4;
    case RosPointType::kFloat64: return 8;
  }
  return 0;
}

RosHeader decode_ros_header(const std::vector<std::uint8_t>& bytes) {
  WireReader r(bytes.data(), bytes.size());
  return read_header(r);
}

RosImage decode_ros_image(const std::vector<std::uint8_t>& bytes) {
  return decode_all(bytes, kRosImage.datatype, [](WireReader& r) {
    RosImage m;
    m.header = read_header(r);
    m.height = r.read<std::uint32_t>();
    m.width = r.read<std::uint32_t>();
    m.encoding = r.string();
    m.is_bigendian = r.read<std::uint8_t>();
    m.step = r.read<std::uint32_t>();
    m.data = r.bytes();
    return m;
  });
}

RosCompressedImage decode_ros_compressed_image(const std::vector<std::uint8_t>& bytes) {
  return decode_all(bytes, kRosCompressedImage.datatype, [](WireReader& r) {
    RosCompressedImage m;
    m.header = read_header(r);
    m.format = r.string();
    m.data = r.bytes();
    return m;
  });
}

RosImu decode_ros_imu(const std::vector<std::uint8_t>& bytes) {
  return decode_all(bytes, kRosImu.datatype, [](WireReader& r) {
    RosImu m;
    m.header = read_header(r);
    read_doubles(r, m.orientation_xyzw);
    read_doubles(r, m.orientation_covariance);
    read_doubles(r, m.angular_velocity);
    read_doubles(r, m.angular_velocity_covariance);
    read_doubles(r, m.linear_acceleration);
    read_doubles(r, m.linear_acceleration_covariance);
    return m;
  });
}

RosPointCloud2 decode_ros_point_cloud2(const std::vector<std::uint8_t>& bytes) {
  return decode_all(bytes, kRosPointCloud2.datatype, [](WireReader& r) {
    RosPointCloud2 m;
    m.header = read_header(r);
    m.height = r.read<std::uint32_t>();
    m.width = r.read<std::uint32_t>();
    const auto num_fields = r.read<std::uint32_t>();
    if (num_fields > r.remaining()) throw WireError("message truncated: " + std::to_string(num_fields) + " fields");
    for (std::uint32_t i = 0; i < num_fields; ++i) {
      RosPointField f;
      f.name = r.string();
      f.offset = r.read<std::uint32_t>();
      f.datatype = r.read<std::uint8_t>();
      f.count = r.read<std::uint32_t>();
      m.fields.push_back(f);
    }
    m.is_bigendian = r.read<std::uint8_t>();
    m.point_step = r.read<std::uint32_t>();
    m.row_step = r.read<std::uint32_t>();
    m.data = r.bytes();
    m.is_dense = r.read<std::uint8_t>();
    return m;
  });
}

RosPoseStamped decode_ros_pose_stamped(const std::vector<std::uint8_t>& bytes) {
  return decode_all(bytes, kRosPoseStamped.datatype, [](WireReader& r) {
    RosPoseStamped m;
    m.header = read_header(r);
    read_doubles(r, m.position);
    read_doubles(r, m.orientation_xyzw);
    return m;
  });
}

std::vector<std::uint8_t> encode(const RosImage& m) {
  WireWriter w;
  write_header(w, m.header);
  w.write(m.height);
  w.write(m.width);
  w.string(m.encoding);
  w.write(m.is_bigendian);
  w.write(m.step);
  w.bytes(m.data.data(), m.data.size());
  return w.release();
}

std::vector<std::uint8_t> encode(const RosImu& m) {
  WireWriter w;
  write_header(w, m.header);
  write_doubles(w, m.orientation_xyzw);
  write_doubles(w, m.orientation_covariance);
  write_doubles(w, m.angular_velocity);
  write_doubles(w, m.angular_velocity_covariance);
  write_doubles(w, m.linear_acceleration);
  write_doubles(w, m.linear_acceleration_covariance);
  return w.release();
}

std::vector<std::uint8_t> encode(const RosPointCloud2& m) {
  WireWriter w;
  write_header(w, m.header);
  w.write(m.height);
  w.write(m.width);
  w.write(static_cast<std::uint32_t>(m.fields.size()));
  for (const RosPointField& f : m.fields) {
    w.string(f.name);
    w.write(f.offset);
    w.write(f.datatype);
    w.write(f.count);
  }
  w.write(m.is_bigendian);
  w.write(m.point_step);
  w.write(m.row_step);
  w.bytes(m.data.data(), m.data.size());
  w.write(m.is_dense);
  return w.release();
}

std::vector<std::uint8_t> encode(const RosPoseStamped& m) {
  WireWriter w;
  write_header(w, m.header);
  write_doubles(w, m.position);
  write_doubles(w, m.orientation_xyzw);
  return w.release();
}

}  // namespace vilslam
