#pragma once
// ROS1 bag files through Debian's rosbag_storage (a storage library only: no ROS master, no workspace).
// Messages are handled as their serialized bytes (ros_messages.h decodes them). Every failure of the
// storage library (not a bag, truncated, unindexed) becomes an InputError naming the file; the record layout
// is checked first (rosbag_layout.h), as the library trusts the lengths a file declares.
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "common/time.h"
#include "io/message_log.h"
#include "io/ros_messages.h"

namespace vilslam {

class BagIn : public MessageLog {
 public:
  explicit BagIn(const std::string& path);
  ~BagIn() override;
  BagIn(const BagIn&) = delete;
  BagIn& operator=(const BagIn&) = delete;

  const std::string& path() const override;
  // Every topic, sorted by name (a topic with connections of two types is an InputError).
  const std::vector<BagTopic>& topics() const override;
  void for_each(const std::string& topic,
                const std::function<void(std::size_t, const std::vector<std::uint8_t>&)>& visit) const override;
  // Cheap when each topic is asked in increasing order.
  std::vector<std::uint8_t> message(const std::string& topic, std::size_t ordinal) override;
  BagWire wire() const override { return BagWire::kRos1; }

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// Writes <path>.partial and renames it to <path> in finish(); destroyed without finish() it removes the
// partial file, so an interrupted export never leaves a bag behind.
class BagOut {
 public:
  explicit BagOut(const std::string& path);
  ~BagOut();
  BagOut(const BagOut&) = delete;
  BagOut& operator=(const BagOut&) = delete;

  // Record time = t_ns (the message's header stamp).
  void write(const std::string& topic, const RosMessageType& type, TimeNs t_ns, const std::vector<std::uint8_t>& bytes);
  void finish();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace vilslam
