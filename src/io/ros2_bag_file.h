#pragma once
// ROS 2 bags in rosbag2's sqlite3 storage (the default of ROS 2 up to Humble; `ros2 bag record -s sqlite3`):
// .db3 files, each with a `topics` table (id, name, type, serialization_format) and a `messages` table (id,
// topic_id, timestamp, data: the CDR bytes). Read through Debian's SQLite, read-only. Refused with an
// InputError naming the file: a serialization other than cdr, a file SQLite cannot read.
#include <memory>

#include "io/message_log.h"

namespace vilslam {

// path: what the user named (a bag folder or one .db3 file); files: the .db3 files in order. Topic types are
// listed by their ROS1 names (sensor_msgs/msg/Image -> sensor_msgs/Image), md5sum "*"; a topic's messages come in
// the order of their record timestamps, then row ids, over the files in order.
std::unique_ptr<IndexedLog> open_sqlite_bag(const std::string& path, const std::vector<std::string>& files);

}  // namespace vilslam
