#pragma once
// ROS 2 bags in rosbag2's sqlite3 storage (the default of ROS 2 up to Humble; `ros2 bag record -s sqlite3`):
// a folder with metadata.yaml and its .db3 files, or one .db3 file. Each .db3 holds a `topics` table (id,
// name, type, serialization_format) and a `messages` table (id, topic_id, timestamp, data: the CDR bytes).
// Read through Debian's SQLite, read-only. Refused with an InputError naming the path: another storage
// (mcap), compressed bags, a serialization other than cdr, a file SQLite cannot read.
#include <memory>

#include "io/message_log.h"

namespace vilslam {

class Ros2Bag : public MessageLog {
 public:
  explicit Ros2Bag(const std::string& path);
  ~Ros2Bag() override;
  Ros2Bag(const Ros2Bag&) = delete;
  Ros2Bag& operator=(const Ros2Bag&) = delete;

  const std::string& path() const override;
  // Types listed by their ROS1 names (sensor_msgs/msg/Image -> sensor_msgs/Image), md5sum "*".
  const std::vector<BagTopic>& topics() const override;
  // Log order: the record timestamp, then the row id, over the bag's files in metadata order.
  void for_each(const std::string& topic,
                const std::function<void(std::size_t, const std::vector<std::uint8_t>&)>& visit) const override;
  std::vector<std::uint8_t> message(const std::string& topic, std::size_t ordinal) override;
  BagWire wire() const override { return BagWire::kCdr; }

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace vilslam
