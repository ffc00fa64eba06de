#pragma once
// The fields of the message types vilslam reads, in .msg order, for either serialization: the ROS1 wire
// format (WireReader, io/ros_wire.h) and ROS 2's CDR (CdrReader, io/cdr_reader.h). Both readers offer
// read<T>(), string(), bytes(), time() and remaining(), and say how they differ: kHeaderSeq (ROS1's
// std_msgs/Header starts with a uint32 seq, ROS 2's has none) and kMaxPadding (bytes a message may end with).
#include <array>
#include <string>
#include <vector>

#include "io/ros_messages.h"
#include "io/ros_wire.h"

namespace vilslam::ros_read {

template <class Reader>
RosHeader header(Reader& r) {
  RosHeader h;
  if constexpr (Reader::kHeaderSeq) h.seq = r.template read<std::uint32_t>();
  h.stamp_ns = r.time();
  h.frame_id = r.string();
  return h;
}

template <class Reader, std::size_t N>
void doubles(Reader& r, std::array<double, N>& values) {
  for (double& v : values) v = r.template read<double>();
}

template <class Reader>
RosImage image(Reader& r) {
  RosImage m;
  m.header = header(r);
  m.height = r.template read<std::uint32_t>();
  m.width = r.template read<std::uint32_t>();
  m.encoding = r.string();
  m.is_bigendian = r.template read<std::uint8_t>();
  m.step = r.template read<std::uint32_t>();
  m.data = r.bytes();
  return m;
}

template <class Reader>
RosCompressedImage compressed_image(Reader& r) {
  RosCompressedImage m;
  m.header = header(r);
  m.format = r.string();
  m.data = r.bytes();
  return m;
}

template <class Reader>
RosImu imu(Reader& r) {
  RosImu m;
  m.header = header(r);
  doubles(r, m.orientation_xyzw);
  doubles(r, m.orientation_covariance);
  doubles(r, m.angular_velocity);
  doubles(r, m.angular_velocity_covariance);
  doubles(r, m.linear_acceleration);
  doubles(r, m.linear_acceleration_covariance);
  return m;
}

template <class Reader>
RosPointCloud2 point_cloud2(Reader& r) {
  RosPointCloud2 m;
  m.header = header(r);
  m.height = r.template read<std::uint32_t>();
  m.width = r.template read<std::uint32_t>();
  const auto num_fields = r.template read<std::uint32_t>();
  if (num_fields > r.remaining()) throw WireError("message truncated: " + std::to_string(num_fields) + " fields");
  for (std::uint32_t i = 0; i < num_fields; ++i) {
    RosPointField f;
    f.name = r.string();
    f.offset = r.template read<std::uint32_t>();
    f.datatype = r.template read<std::uint8_t>();
    f.count = r.template read<std::uint32_t>();
    m.fields.push_back(f);
  }
  m.is_bigendian = r.template read<std::uint8_t>();
  m.point_step = r.template read<std::uint32_t>();
  m.row_step = r.template read<std::uint32_t>();
  m.data = r.bytes();
  m.is_dense = r.template read<std::uint8_t>();
  return m;
}

template <class Reader>
RosPoseStamped pose_stamped(Reader& r) {
  RosPoseStamped m;
  m.header = header(r);
  doubles(r, m.position);
  doubles(r, m.orientation_xyzw);
  return m;
}

// Reads a whole message with read (one of the above); more than Reader::kMaxPadding bytes left over is a
// WireError (the message is of another type).
template <class Reader, class Read>
auto whole(const std::vector<std::uint8_t>& bytes, const char* datatype, Read read) {
  Reader r(bytes.data(), bytes.size());
  auto message = read(r);
  if (r.remaining() > Reader::kMaxPadding) {
    throw WireError(std::to_string(r.remaining()) + " bytes left over after a " + datatype +
                    " (is the message of another type?)");
  }
  return message;
}

}  // namespace vilslam::ros_read
