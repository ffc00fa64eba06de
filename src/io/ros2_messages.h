#pragma once
// ROS 2 messages as rosbag2 stores them (CDR, io/cdr_reader.h) decoded into the structs of ros_messages.h:
// ROS 2's sensor_msgs / geometry_msgs have ROS1's fields except the header (builtin_interfaces/Time stamp:
// int32 sec + uint32 nanosec, frame_id; no seq, left 0).
// Decoders throw WireError when the bytes end early or more than padding is left over.
#include <string>
#include <vector>

#include "io/ros_messages.h"

namespace vilslam {

RosImage decode_cdr_image(const std::vector<std::uint8_t>& bytes);
RosCompressedImage decode_cdr_compressed_image(const std::vector<std::uint8_t>& bytes);
RosImu decode_cdr_imu(const std::vector<std::uint8_t>& bytes);
RosPointCloud2 decode_cdr_point_cloud2(const std::vector<std::uint8_t>& bytes);
RosPoseStamped decode_cdr_pose_stamped(const std::vector<std::uint8_t>& bytes);

// A ROS 2 type name ("sensor_msgs/msg/Image") as the ROS1 name the readers key on ("sensor_msgs/Image");
// other names unchanged.
std::string ros1_type_name(const std::string& ros2_type);

}  // namespace vilslam
