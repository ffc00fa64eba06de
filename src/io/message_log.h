#pragma once
// A recorded log of serialized messages by topic, as the bag readers see it: a ROS1 bag (io/rosbag_file.h) or
// a ROS 2 bag in sqlite3 (io/ros2_bag_file.h) or MCAP (io/mcap_file.h) storage. Topic types carry ROS1 names ("sensor_msgs/Image"); wire() says how the
// bytes of a message are serialized.
#include <cstdint>
#include <functional>
#include <map>
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

// A log whose messages were located when it was opened (the ROS 2 storages): per topic, in log order, the
// ids that fetch turns into a message's bytes. Its messages are CDR.
class IndexedLog : public MessageLog {
 public:
  using Fetch = std::function<std::vector<std::uint8_t>(std::size_t id)>;
  IndexedLog(std::string path, std::vector<BagTopic> topics, std::map<std::string, std::vector<std::size_t>> ids,
             Fetch fetch);
  const std::string& path() const override { return path_; }
  const std::vector<BagTopic>& topics() const override { return topics_; }
  void for_each(const std::string& topic,
                const std::function<void(std::size_t, const std::vector<std::uint8_t>&)>& visit) const override;
  std::vector<std::uint8_t> message(const std::string& topic, std::size_t ordinal) override;
  BagWire wire() const override { return BagWire::kCdr; }

  // Each message fetched is a zstd frame (rosbag2's compression_mode MESSAGE): decompress it.
  void decompress_messages() { zstd_messages_ = true; }
  // Holds resource (e.g. the bag's decompressed files) as long as the log, and drops it after the storage.
  void keep(std::shared_ptr<void> resource) { kept_.push_back(std::move(resource)); }

 private:
  const std::vector<std::size_t>& ids_of(const std::string& topic) const;
  std::vector<std::uint8_t> fetch(std::size_t id) const;
  std::vector<std::shared_ptr<void>> kept_;  // first: destroyed last
  std::string path_;
  std::vector<BagTopic> topics_;
  std::map<std::string, std::vector<std::size_t>> ids_;
  Fetch fetch_;
  bool zstd_messages_ = false;
};

// A ROS 2 bag: a folder holding metadata.yaml, or one .db3 or .mcap file.
bool is_ros2_bag(const std::string& path);
// A ROS1 .bag file or a ROS 2 bag: its folder (metadata.yaml: storage_identifier sqlite3 or mcap,
// relative_file_paths; a compressed bag is refused) or one file (InputError naming the path when it cannot
// be opened).
std::unique_ptr<MessageLog> open_message_log(const std::string& path);

}  // namespace vilslam
