#pragma once
// Writes a dataset as a ROS 2 bag in rosbag2's sqlite3 storage for the ROS 2 bag tests: the messages are
// serialized by eProsima Fast CDR (the CDR library of ROS 2's default middleware), so the reader's own CDR
// code is checked against an independent implementation; the tables follow rosbag2's schema.
#include <fastcdr/Cdr.h>
#include <fastcdr/FastBuffer.h>
#include <sqlite3.h>
#include <zstd.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include "io/dataset.h"
#include "io/ros_convert.h"

namespace vilslam::test {

struct Ros2BagOptions {
  bool big_endian = false;  // CDR_BE instead of CDR_LE
  int files = 1;            // the messages split over this many .db3 files (topic ids differ between them)
  std::string compression_mode;  // rosbag2's zstd compression: "" none, "file" (each .db3 as .db3.zstd), "message"
};

inline std::vector<std::uint8_t> zstd_compress(const std::uint8_t* data, std::size_t size) {
  std::vector<std::uint8_t> out(ZSTD_compressBound(size));
  out.resize(ZSTD_compress(out.data(), out.size(), data, size, 3));
  return out;
}

class CdrMessage {
 public:
  explicit CdrMessage(bool big_endian)
      : cdr_(buffer_, big_endian ? eprosima::fastcdr::Cdr::BIG_ENDIANNESS : eprosima::fastcdr::Cdr::LITTLE_ENDIANNESS,
             eprosima::fastcdr::Cdr::DDS_CDR) {
    cdr_.serialize_encapsulation();
  }
  eprosima::fastcdr::Cdr& cdr() { return cdr_; }
  void header(const RosHeader& h) {
    cdr_ << static_cast<std::int32_t>(h.stamp_ns / 1'000'000'000) << static_cast<std::uint32_t>(h.stamp_ns % 1'000'000'000)
         << h.frame_id;
  }
  template <std::size_t N>
  void doubles(const std::array<double, N>& values) {
    for (double v : values) cdr_ << v;
  }
  std::vector<std::uint8_t> bytes() const {
    const auto* p = reinterpret_cast<const std::uint8_t*>(buffer_.getBuffer());
    return std::vector<std::uint8_t>(p, p + cdr_.getSerializedDataLength());
  }

 private:
  eprosima::fastcdr::FastBuffer buffer_;
  eprosima::fastcdr::Cdr cdr_;
};

inline std::vector<std::uint8_t> cdr_bytes(const RosImage& m, bool big_endian) {
  CdrMessage c(big_endian);
  c.header(m.header);
  c.cdr() << m.height << m.width << m.encoding << m.is_bigendian << m.step << m.data;
  return c.bytes();
}

inline std::vector<std::uint8_t> cdr_bytes(const RosImu& m, bool big_endian) {
  CdrMessage c(big_endian);
  c.header(m.header);
  c.doubles(m.orientation_xyzw);
  c.doubles(m.orientation_covariance);
  c.doubles(m.angular_velocity);
  c.doubles(m.angular_velocity_covariance);
  c.doubles(m.linear_acceleration);
  c.doubles(m.linear_acceleration_covariance);
  return c.bytes();
}

inline std::vector<std::uint8_t> cdr_bytes(const RosPointCloud2& m, bool big_endian) {
  CdrMessage c(big_endian);
  c.header(m.header);
  c.cdr() << m.height << m.width << static_cast<std::uint32_t>(m.fields.size());
  for (const RosPointField& f : m.fields) c.cdr() << f.name << f.offset << f.datatype << f.count;
  c.cdr() << (m.is_bigendian != 0) << m.point_step << m.row_step << m.data << (m.is_dense != 0);
  return c.bytes();
}

inline std::vector<std::uint8_t> cdr_bytes(const RosPoseStamped& m, bool big_endian) {
  CdrMessage c(big_endian);
  c.header(m.header);
  c.doubles(m.position);
  c.doubles(m.orientation_xyzw);
  return c.bytes();
}

inline void sql(sqlite3* db, const std::string& statement) {
  char* error = nullptr;
  if (sqlite3_exec(db, statement.c_str(), nullptr, nullptr, &error) != SQLITE_OK) {
    const std::string what = error ? error : "?";
    sqlite3_free(error);
    throw std::runtime_error("sqlite: " + what + " in " + statement);
  }
}

struct Ros2Message {
  std::string topic;
  TimeNs t_ns;
  std::vector<std::uint8_t> data;
};

// Topic and ROS 2 type of each stream, as export-bag names the topics.
inline const std::vector<std::pair<std::string, std::string>>& ros2_topics() {
  static const std::vector<std::pair<std::string, std::string>> topics = {
      {"/imu0", "sensor_msgs/msg/Imu"},
      {"/cam0/image_raw", "sensor_msgs/msg/Image"},
      {"/cam1/image_raw", "sensor_msgs/msg/Image"},
      {"/points_raw", "sensor_msgs/msg/PointCloud2"},
      {"/ground_truth", "geometry_msgs/msg/PoseStamped"}};
  return topics;
}

// The reader's events as CDR messages, in time order.
inline std::vector<Ros2Message> ros2_messages(DatasetReader& reader, bool be) {
  std::vector<Ros2Message> messages;
  reader.rewind();
  while (const auto e = reader.next()) {
    if (const auto* imu = std::get_if<ImuSample>(&e->data)) {
      messages.push_back({"/imu0", imu->t_ns, cdr_bytes(ros_imu_from_sample(*imu), be)});
    } else if (const auto* f = std::get_if<StereoFrame>(&e->data)) {
      messages.push_back({"/cam0/image_raw", f->t_ns, cdr_bytes(ros_image_from_grey(f->left, f->t_ns, "cam0"), be)});
      messages.push_back({"/cam1/image_raw", f->t_ns, cdr_bytes(ros_image_from_grey(f->right, f->t_ns, "cam1"), be)});
    } else if (const auto* s = std::get_if<LidarScan>(&e->data)) {
      messages.push_back({"/points_raw", s->t_ns, cdr_bytes(velodyne_point_cloud2(*s, "lidar0"), be)});
    } else if (const auto* gt = std::get_if<GroundTruthState>(&e->data)) {
      messages.push_back({"/ground_truth", gt->t_ns, cdr_bytes(ros_pose_from_state(*gt), be)});
    }
  }
  return messages;
}

// The reader's events as a bag folder dir (metadata.yaml, dir/NAME_i.db3).
inline void write_ros2_bag(DatasetReader& reader, const std::filesystem::path& dir, const Ros2BagOptions& options = {}) {
  const std::vector<Ros2Message> messages = ros2_messages(reader, options.big_endian);
  const auto& topics = ros2_topics();
  std::filesystem::create_directories(dir);
  const std::string name = dir.filename().string();
  std::string files_yaml;
  const std::size_t per_file = (messages.size() + options.files - 1) / options.files;
  for (int f = 0; f < options.files; ++f) {
    const std::string file = name + "_" + std::to_string(f) + ".db3";
    files_yaml += "    - " + file + "\n";
    sqlite3* db = nullptr;
    sqlite3_open((dir / file).string().c_str(), &db);
    sql(db,
        "CREATE TABLE schema(schema_version INTEGER PRIMARY KEY, ros_distro TEXT NOT NULL);"
        "INSERT INTO schema VALUES(3, 'humble');"
        "CREATE TABLE topics(id INTEGER PRIMARY KEY, name TEXT NOT NULL, type TEXT NOT NULL,"
        " serialization_format TEXT NOT NULL, offered_qos_profiles TEXT NOT NULL);"
        "CREATE TABLE messages(id INTEGER PRIMARY KEY, topic_id INTEGER NOT NULL, timestamp INTEGER NOT NULL,"
        " data BLOB NOT NULL);"
        "CREATE INDEX timestamp_idx ON messages (timestamp ASC);"
        "BEGIN TRANSACTION;");
    std::map<std::string, int> id_of;
    for (std::size_t k = 0; k < topics.size(); ++k) {
      // Ids numbered the other way round in every other file: the reader must map them by name.
      const int id = f % 2 == 0 ? static_cast<int>(k) + 1 : static_cast<int>(topics.size() - k);
      id_of[topics[k].first] = id;
      sql(db, "INSERT INTO topics VALUES(" + std::to_string(id) + ", '" + topics[k].first + "', '" + topics[k].second +
                  "', 'cdr', '')");
    }
    sqlite3_stmt* insert = nullptr;
    sqlite3_prepare_v2(db, "INSERT INTO messages (topic_id, timestamp, data) VALUES (?, ?, ?)", -1, &insert, nullptr);
    for (std::size_t i = f * per_file; i < std::min(messages.size(), (f + 1) * per_file); ++i) {
      const Ros2Message& m = messages[i];
      sqlite3_bind_int(insert, 1, id_of.at(m.topic));
      sqlite3_bind_int64(insert, 2, m.t_ns);
      const std::vector<std::uint8_t> data =
          options.compression_mode == "message" ? zstd_compress(m.data.data(), m.data.size()) : m.data;
      sqlite3_bind_blob(insert, 3, data.data(), static_cast<int>(data.size()), SQLITE_TRANSIENT);
      if (sqlite3_step(insert) != SQLITE_DONE) throw std::runtime_error("sqlite: insert failed");
      sqlite3_reset(insert);
    }
    sqlite3_finalize(insert);
    sql(db, "COMMIT;");
    sqlite3_close(db);
    if (options.compression_mode == "file") {  // the file as one zstd frame, listed under its .zstd name
      std::ifstream in(dir / file, std::ios::binary);
      const std::string plain((std::istreambuf_iterator<char>(in)), {});
      const auto packed = zstd_compress(reinterpret_cast<const std::uint8_t*>(plain.data()), plain.size());
      std::ofstream(dir / (file + ".zstd"), std::ios::binary)
          .write(reinterpret_cast<const char*>(packed.data()), static_cast<std::streamsize>(packed.size()));
      std::filesystem::remove(dir / file);
      files_yaml.replace(files_yaml.rfind(file), file.size(), file + ".zstd");
    }
  }
  std::ofstream(dir / "metadata.yaml") << "rosbag2_bagfile_information:\n  version: 5\n  storage_identifier: sqlite3\n"
                                          "  relative_file_paths:\n"
                                       << files_yaml << "  compression_format: \""
                                       << (options.compression_mode.empty() ? "" : "zstd") << "\"\n  compression_mode: \""
                                       << options.compression_mode << "\"\n";
}

}  // namespace vilslam::test
