// Wire (de)serialization of the ROS1 message types in ros_messages.h (the fields read: io/ros_message_read.h).
#include "io/ros_messages.h"

#include "io/ros_message_read.h"
#include "io/ros_wire.h"

namespace vilslam {
namespace {

void write_header(WireWriter& w, const RosHeader& h) {
  w.write(h.seq);
  w.time(h.stamp_ns);
  w.string(h.frame_id);
}

template <std::size_t N>
void write_doubles(WireWriter& w, const std::array<double, N>& values) {
  for (double v : values) w.write(v);
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
  return ros_read::header(r);
}

RosImage decode_ros_image(const std::vector<std::uint8_t>& bytes) {
  return ros_read::whole<WireReader>(bytes, kRosImage.datatype, ros_read::image<WireReader>);
}

RosCompressedImage decode_ros_compressed_image(const std::vector<std::uint8_t>& bytes) {
  return ros_read::whole<WireReader>(bytes, kRosCompressedImage.datatype, ros_read::compressed_image<WireReader>);
}

RosImu decode_ros_imu(const std::vector<std::uint8_t>& bytes) {
  return ros_read::whole<WireReader>(bytes, kRosImu.datatype, ros_read::imu<WireReader>);
}

RosPointCloud2 decode_ros_point_cloud2(const std::vector<std::uint8_t>& bytes) {
  return ros_read::whole<WireReader>(bytes, kRosPointCloud2.datatype, ros_read::point_cloud2<WireReader>);
}

RosPoseStamped decode_ros_pose_stamped(const std::vector<std::uint8_t>& bytes) {
  return ros_read::whole<WireReader>(bytes, kRosPoseStamped.datatype, ros_read::pose_stamped<WireReader>);
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
