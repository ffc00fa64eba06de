#pragma once
// Which topic of a bag feeds each stream: found by message type, overridable per role.
#include <map>
#include <string>
#include <vector>

#include "io/message_log.h"
#include "io/ros_messages.h"

namespace vilslam {

// Empty: the bag has no such stream.
struct BagTopics {
  std::string cam0, cam1;   // sensor_msgs/Image or CompressedImage
  std::string imu0;         // sensor_msgs/Imu (required)
  std::string lidar0;       // sensor_msgs/PointCloud2
  std::string groundtruth;  // geometry_msgs/PoseStamped, pose of I in W
};

// overrides: role (cam0, cam1, imu0, lidar0, groundtruth) -> topic. A role left open takes the only topic
// of its type; two image topics are the stereo pair in name order (cam0 the first, unless the names say
// right/left). An unknown role is std::invalid_argument; a topic not in the bag, of the wrong type, or an
// ambiguous choice is an InputError naming the bag and the topics.
BagTopics choose_bag_topics(const MessageLog& bag, const std::map<std::string, std::string>& overrides);

}  // namespace vilslam
