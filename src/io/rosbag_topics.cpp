// Choosing the topics of a bag by type (docs/formats.md, "ROS1 bags").
#include "io/rosbag_topics.h"

#include <algorithm>
#include <functional>
#include <stdexcept>

#include "common/error.h"

namespace vilslam {
namespace {

bool is_image_type(const std::string& datatype) {
  return datatype == kRosImage.datatype || datatype == kRosCompressedImage.datatype;
}

std::string list(const std::vector<std::string>& names) {
  std::string out;
  for (const std::string& n : names) out += (out.empty() ? "" : ", ") + n;
  return out.empty() ? "none" : out;
}

std::vector<std::string> topics_where(const MessageLog& bag, const std::function<bool(const std::string&)>& accept) {
  std::vector<std::string> names;
  for (const BagTopic& t : bag.topics()) {
    if (accept(t.datatype)) names.push_back(t.topic);
  }
  return names;
}

std::vector<std::string> topics_of_type(const MessageLog& bag, const char* datatype) {
  return topics_where(bag, [datatype](const std::string& d) { return d == datatype; });
}

// The override of a role, checked to be in the bag with an accepted type; "" when not overridden.
std::string given_topic(const MessageLog& bag, const std::map<std::string, std::string>& overrides, const std::string& role,
                        const std::vector<std::string>& of_type, const std::string& type_names) {
  const auto it = overrides.find(role);
  if (it == overrides.end()) return {};
  const std::string& topic = it->second;
  const auto t = std::find_if(bag.topics().begin(), bag.topics().end(), [&](const BagTopic& b) { return b.topic == topic; });
  if (t == bag.topics().end()) {
    std::vector<std::string> all;
    for (const BagTopic& b : bag.topics()) all.push_back(b.topic);
    throw InputError(bag.path(), "topic " + topic + " (given for " + role + ") is not in the bag; its topics: " + list(all));
  }
  if (std::find(of_type.begin(), of_type.end(), topic) == of_type.end()) {
    throw InputError(bag.path(), "topic " + topic + " (given for " + role + ") is " + t->datatype + ", expected " + type_names);
  }
  return topic;
}

// The one topic of a type (or none); several are an InputError asking for the role's override.
std::string only_topic(const MessageLog& bag, const std::string& role, const std::vector<std::string>& of_type,
                       const std::string& type_name) {
  if (of_type.size() > 1) {
    throw InputError(bag.path(), std::to_string(of_type.size()) + " " + type_name + " topics (" + list(of_type) +
                                     "): choose one with --topic " + role + "=TOPIC");
  }
  return of_type.empty() ? std::string() : of_type.front();
}

bool mentions(const std::string& topic, const char* word) { return topic.find(word) != std::string::npos; }

}  // namespace

BagTopics choose_bag_topics(const MessageLog& bag, const std::map<std::string, std::string>& overrides) {
  for (const auto& [role, topic] : overrides) {
    if (role != "cam0" && role != "cam1" && role != "imu0" && role != "lidar0" && role != "groundtruth") {
      throw std::invalid_argument("unknown topic role '" + role + "' (cam0, cam1, imu0, lidar0, groundtruth)");
    }
  }
  const std::string image_types = std::string(kRosImage.datatype) + " or " + kRosCompressedImage.datatype;
  const auto images = topics_where(bag, is_image_type);
  const auto imus = topics_of_type(bag, kRosImu.datatype);
  const auto clouds = topics_of_type(bag, kRosPointCloud2.datatype);
  const auto poses = topics_of_type(bag, kRosPoseStamped.datatype);

  BagTopics t;
  t.cam0 = given_topic(bag, overrides, "cam0", images, image_types);
  t.cam1 = given_topic(bag, overrides, "cam1", images, image_types);
  if (t.cam0.empty() || t.cam1.empty()) {
    std::vector<std::string> open;
    for (const std::string& name : images) {
      if (name != t.cam0 && name != t.cam1) open.push_back(name);
    }
    const std::size_t needed = (t.cam0.empty() ? 1 : 0) + (t.cam1.empty() ? 1 : 0);
    if (open.size() != needed && !(open.empty() && needed == 2)) {
      throw InputError(bag.path(), std::to_string(images.size()) + " image topics (" + list(images) +
                                       "): name the stereo pair with --topic cam0=TOPIC --topic cam1=TOPIC");
    }
    if (needed == 2 && open.size() == 2) {
      if (mentions(open[0], "right") && mentions(open[1], "left")) std::swap(open[0], open[1]);
      t.cam0 = open[0];
      t.cam1 = open[1];
    } else if (needed == 1) {
      (t.cam0.empty() ? t.cam0 : t.cam1) = open.front();
    }
  }
  t.imu0 = given_topic(bag, overrides, "imu0", imus, kRosImu.datatype);
  if (t.imu0.empty()) t.imu0 = only_topic(bag, "imu0", imus, kRosImu.datatype);
  if (t.imu0.empty()) throw InputError(bag.path(), std::string("no ") + kRosImu.datatype + " topic: an IMU is required");
  t.lidar0 = given_topic(bag, overrides, "lidar0", clouds, kRosPointCloud2.datatype);
  if (t.lidar0.empty()) t.lidar0 = only_topic(bag, "lidar0", clouds, kRosPointCloud2.datatype);
  t.groundtruth = given_topic(bag, overrides, "groundtruth", poses, kRosPoseStamped.datatype);
  if (t.groundtruth.empty()) t.groundtruth = only_topic(bag, "groundtruth", poses, kRosPoseStamped.datatype);
  return t;
}

}  // namespace vilslam
