#pragma once
// The ROS1 message types vilslam reads and writes, as plain structs with their wire (de)serialization
// (ros_wire.h). Field order and types follow the .msg definitions in ros_message_types.cpp exactly.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "common/time.h"

namespace vilslam {

// What a bag's connection record names: type, MD5 of the definition, and the full definition text.
struct RosMessageType {
  const char* datatype;
  const char* md5sum;
  const char* definition;
};
extern const RosMessageType kRosImage;            // sensor_msgs/Image
extern const RosMessageType kRosCompressedImage;  // sensor_msgs/CompressedImage
extern const RosMessageType kRosImu;              // sensor_msgs/Imu
extern const RosMessageType kRosPointCloud2;      // sensor_msgs/PointCloud2
extern const RosMessageType kRosPoseStamped;      // geometry_msgs/PoseStamped

struct RosHeader {  // std_msgs/Header
  std::uint32_t seq = 0;
  TimeNs stamp_ns = 0;
  std::string frame_id;
};

struct RosImage {
  RosHeader header;
  std::uint32_t height = 0, width = 0;
  std::string encoding;
  std::uint8_t is_bigendian = 0;
  std::uint32_t step = 0;  // bytes per row
  std::vector<std::uint8_t> data;
};

struct RosCompressedImage {
  RosHeader header;
  std::string format;  // e.g. "png", "jpeg", "mono8; png compressed"
  std::vector<std::uint8_t> data;
};

struct RosImu {
  RosHeader header;
  std::array<double, 4> orientation_xyzw{0, 0, 0, 1};
  std::array<double, 9> orientation_covariance{};
  std::array<double, 3> angular_velocity{};
  std::array<double, 9> angular_velocity_covariance{};
  std::array<double, 3> linear_acceleration{};
  std::array<double, 9> linear_acceleration_covariance{};
};

// sensor_msgs/PointField datatype codes.
enum class RosPointType : std::uint8_t { kInt8 = 1, kUint8, kInt16, kUint16, kInt32, kUint32, kFloat32, kFloat64 };

struct RosPointField {
  std::string name;
  std::uint32_t offset = 0;
  std::uint8_t datatype = 0;  // RosPointType
  std::uint32_t count = 1;
};

struct RosPointCloud2 {
  RosHeader header;
  std::uint32_t height = 1, width = 0;
  std::vector<RosPointField> fields;
  std::uint8_t is_bigendian = 0;
  std::uint32_t point_step = 0, row_step = 0;
  std::vector<std::uint8_t> data;
  std::uint8_t is_dense = 1;
};

struct RosPoseStamped {
  RosHeader header;
  std::array<double, 3> position{};
  std::array<double, 4> orientation_xyzw{0, 0, 0, 1};
};

// Decoders throw WireError when the bytes end early or do not match the type exactly (bytes left over).
RosHeader decode_ros_header(const std::vector<std::uint8_t>& bytes);  // the leading Header of any stamped message
RosImage decode_ros_image(const std::vector<std::uint8_t>& bytes);
RosCompressedImage decode_ros_compressed_image(const std::vector<std::uint8_t>& bytes);
RosImu decode_ros_imu(const std::vector<std::uint8_t>& bytes);
RosPointCloud2 decode_ros_point_cloud2(const std::vector<std::uint8_t>& bytes);
RosPoseStamped decode_ros_pose_stamped(const std::vector<std::uint8_t>& bytes);

std::vector<std::uint8_t> encode(const RosImage& m);
std::vector<std::uint8_t> encode(const RosImu& m);
std::vector<std::uint8_t> encode(const RosPointCloud2& m);
std::vector<std::uint8_t> encode(const RosPoseStamped& m);

// Size in bytes of one element of a PointField datatype; 0 for an unknown code.
std::size_t ros_point_type_size(std::uint8_t datatype);

}  // namespace vilslam
