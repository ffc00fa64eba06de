// CDR decoding of the ROS 2 message types vilslam reads (fields: io/ros_message_read.h).
#include "io/ros2_messages.h"

#include "io/cdr_reader.h"
#include "io/ros_message_read.h"

namespace vilslam {
RosImage decode_cdr_image(const std::vector<std::uint8_t>& bytes) {
  return ros_read::whole<CdrReader>(bytes, kRosImage.datatype, ros_read::image<CdrReader>);
}

RosCompressedImage decode_cdr_compressed_image(const std::vector<std::uint8_t>& bytes) {
  return ros_read::whole<CdrReader>(bytes, kRosCompressedImage.datatype, ros_read::compressed_image<CdrReader>);
}

RosImu decode_cdr_imu(const std::vector<std::uint8_t>& bytes) {
  return ros_read::whole<CdrReader>(bytes, kRosImu.datatype, ros_read::imu<CdrReader>);
}

RosPointCloud2 decode_cdr_point_cloud2(const std::vector<std::uint8_t>& bytes) {
  return ros_read::whole<CdrReader>(bytes, kRosPointCloud2.datatype, ros_read::point_cloud2<CdrReader>);
}

RosPoseStamped decode_cdr_pose_stamped(const std::vector<std::uint8_t>& bytes) {
  return ros_read::whole<CdrReader>(bytes, kRosPoseStamped.datatype, ros_read::pose_stamped<CdrReader>);
}

std::string ros1_type_name(const std::string& ros2_type) {
  const auto at = ros2_type.find("/msg/");
  if (at == std::string::npos) return ros2_type;
  return ros2_type.substr(0, at) + "/" + ros2_type.substr(at + 5);
}

}  // namespace vilslam
