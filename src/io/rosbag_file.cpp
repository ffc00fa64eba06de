// BagIn / BagOut over rosbag_storage. The only file that includes ROS headers: a raw message type with
// the ROS traits lets rosbag_storage write bytes serialized by ros_messages.cpp.
#include "io/rosbag_file.h"

#include <rosbag/bag.h>
#include <rosbag/view.h>

#include <algorithm>
#include <filesystem>
#include <map>

#include "common/error.h"
#include "io/rosbag_layout.h"

namespace vilslam {
namespace {

struct RawMessage {
  const RosMessageType* type = nullptr;
  const std::vector<std::uint8_t>* bytes = nullptr;
};

}  // namespace
}  // namespace vilslam

namespace ros {
namespace message_traits {
template <>
struct MD5Sum<vilslam::RawMessage> {
  static const char* value(const vilslam::RawMessage& m) { return m.type->md5sum; }
};
template <>
struct DataType<vilslam::RawMessage> {
  static const char* value(const vilslam::RawMessage& m) { return m.type->datatype; }
};
template <>
struct Definition<vilslam::RawMessage> {
  static const char* value(const vilslam::RawMessage& m) { return m.type->definition; }
};
}  // namespace message_traits
namespace serialization {
template <>
struct Serializer<vilslam::RawMessage> {
  template <typename Stream>
  static void write(Stream& stream, const vilslam::RawMessage& m) {
    if (!m.bytes->empty()) std::memcpy(stream.advance(m.bytes->size()), m.bytes->data(), m.bytes->size());
  }
  static std::uint32_t serializedLength(const vilslam::RawMessage& m) { return m.bytes->size(); }
};
}  // namespace serialization
}  // namespace ros

namespace vilslam {
namespace {

// The storage library's words for a bag it cannot read, made readable.
std::string bag_problem(const std::exception& e) {
  const std::string what = e.what();
  if (dynamic_cast<const rosbag::BagUnindexedException*>(&e)) {
    return "bag is not indexed (an interrupted recording; `rosbag reindex` repairs it)";
  }
  return "cannot read the bag (truncated or not a ROS1 bag): " + what;
}

std::vector<std::uint8_t> bytes_of(const rosbag::MessageInstance& m) {
  std::vector<std::uint8_t> bytes(m.size());
  ros::serialization::OStream stream(bytes.data(), static_cast<std::uint32_t>(bytes.size()));
  m.write(stream);
  return bytes;
}

}  // namespace

struct BagIn::Impl {
  std::string path;
  rosbag::Bag bag;
  std::vector<BagTopic> topics;
  struct Cursor {
    std::unique_ptr<rosbag::View> view;
    rosbag::View::iterator it;
    std::size_t ordinal = 0;
  };
  std::map<std::string, Cursor> cursors;

  void reset(const std::string& topic, Cursor& c) {
    c.view = std::make_unique<rosbag::View>(bag, rosbag::TopicQuery(topic));
    c.it = c.view->begin();
    c.ordinal = 0;
  }
};

BagIn::BagIn(const std::string& path) : impl_(std::make_unique<Impl>()) {
  impl_->path = path;
  if (!std::filesystem::is_regular_file(path)) throw InputError(path, "bag file does not exist");
  check_bag_layout(path);
  try {
    impl_->bag.open(path, rosbag::bagmode::Read);
    rosbag::View all(impl_->bag);
    std::map<std::string, BagTopic> by_name;
    for (const rosbag::ConnectionInfo* c : all.getConnections()) {
      BagTopic& t = by_name[c->topic];
      if (!t.datatype.empty() && t.datatype != c->datatype) {
        throw InputError(path, "topic " + c->topic + " has messages of two types, " + t.datatype + " and " + c->datatype);
      }
      t.topic = c->topic;
      t.datatype = c->datatype;
      t.md5sum = c->md5sum;
    }
    for (auto& [name, t] : by_name) {
      t.messages = rosbag::View(impl_->bag, rosbag::TopicQuery(name)).size();
      impl_->topics.push_back(t);
    }
  } catch (const rosbag::BagException& e) {
    throw InputError(path, bag_problem(e));
  }
}

BagIn::~BagIn() = default;

const std::string& BagIn::path() const { return impl_->path; }
const std::vector<BagTopic>& BagIn::topics() const { return impl_->topics; }

void BagIn::for_each(const std::string& topic,
                     const std::function<void(std::size_t, const std::vector<std::uint8_t>&)>& visit) const {
  try {
    std::size_t ordinal = 0;
    for (const rosbag::MessageInstance& m : rosbag::View(impl_->bag, rosbag::TopicQuery(topic))) {
      visit(ordinal++, bytes_of(m));
    }
  } catch (const rosbag::BagException& e) {
    throw InputError(impl_->path, "topic " + topic + ": " + bag_problem(e));
  }
}

std::vector<std::uint8_t> BagIn::message(const std::string& topic, std::size_t ordinal) {
  try {
    Impl::Cursor& c = impl_->cursors[topic];
    if (!c.view || ordinal < c.ordinal) impl_->reset(topic, c);
    while (c.ordinal < ordinal && c.it != c.view->end()) {
      ++c.it;
      ++c.ordinal;
    }
    if (c.it == c.view->end()) {
      throw InputError(impl_->path, "topic " + topic + " has no message " + std::to_string(ordinal));
    }
    return bytes_of(*c.it);
  } catch (const rosbag::BagException& e) {
    throw InputError(impl_->path, "topic " + topic + ": " + bag_problem(e));
  }
}

struct BagOut::Impl {
  std::string path;
  std::string partial;
  rosbag::Bag bag;
  bool finished = false;
};

BagOut::BagOut(const std::string& path) : impl_(std::make_unique<Impl>()) {
  impl_->path = path;
  impl_->partial = path + ".partial";
  try {
    impl_->bag.open(impl_->partial, rosbag::bagmode::Write);
  } catch (const rosbag::BagException& e) {
    throw InputError(impl_->partial, std::string("cannot create the bag: ") + e.what());
  }
}

BagOut::~BagOut() {
  if (impl_->finished) return;
  impl_->bag.close();
  std::error_code ec;
  std::filesystem::remove(impl_->partial, ec);
}

void BagOut::write(const std::string& topic, const RosMessageType& type, TimeNs t_ns,
                   const std::vector<std::uint8_t>& bytes) {
  if (t_ns < 0) throw std::invalid_argument("bag record time before 1970");
  ros::Time time;
  time.fromNSec(static_cast<std::uint64_t>(std::max<TimeNs>(t_ns, 1)));  // rosbag refuses 0 (ros::TIME_MIN)
  try {
    impl_->bag.write(topic, time, RawMessage{&type, &bytes});
  } catch (const rosbag::BagException& e) {
    throw std::runtime_error(impl_->partial + ": cannot write topic " + topic + ": " + e.what());
  }
}

void BagOut::finish() {
  try {
    impl_->bag.close();
  } catch (const rosbag::BagException& e) {
    throw std::runtime_error(impl_->partial + ": cannot finish the bag: " + e.what());
  }
  std::filesystem::rename(impl_->partial, impl_->path);
  impl_->finished = true;
}

}  // namespace vilslam
