#pragma once
// A recorded log of serialized messages by topic, as the bag readers see it: a ROS1 bag (io/rosbag_file.h) or
// a ROS 2 bag (io/ros2_bag_file.h). Topic types carry ROS1 names ("sensor_msgs/Image"); wire() says how the
// bytes of a message are serialized.
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace vilslam {

struct BagTopic {
  std::string topic;
  std::string datatype;  // ROS1 name (a ROS 2 bag's sensor_msgs/msg/Image is listed as sensor_msgs/Image)
  std::string md5sum;    // ROS1 definition MD5; "*" when the log has none (ROS 2)
  std::size_t messages = 0;
};

enum class BagWire { kRos1, kCdr };

class MessageLog {
 public:
  virtual ~MessageLog() = default;
  virtual const std::string& path() const = 0;
  // Every topic, sorted by name.
  virtual const std::vector<BagTopic>& topics() const = 0;
  // Visits the messages of a topic in log order: visit(ordinal, serialized bytes).
  virtual void for_each(const std::string& topic,
                        const std::function<void(std::size_t, const std::vector<std::uint8_t>&)>& visit) const = 0;
  // The bytes of message `ordinal` of a topic.
  virtual std::vector<std::uint8_t> message(const std::string& topic, std::size_t ordinal) = 0;
  virtual BagWire wire() const = 0;
};

// A ROS 2 bag: a folder holding metadata.yaml, or one .db3 file.
bool is_ros2_bag(const std::string& path);
// A ROS1 .bag file or a ROS 2 bag (InputError naming the path when it cannot be opened).
std::unique_ptr<MessageLog> open_message_log(const std::string& path);

}  // namespace vilslam
