#include "io/ros2_bag_file.h"

#include <sqlite3.h>
#include <yaml-cpp/yaml.h>

#include <filesystem>
#include <map>

#include "common/error.h"
#include "io/ros2_messages.h"
#include "io/rosbag_file.h"

namespace vilslam {
namespace {

namespace fs = std::filesystem;

struct DbClose {
  void operator()(sqlite3* db) const { sqlite3_close(db); }
};
struct StmtFinalize {
  void operator()(sqlite3_stmt* s) const { sqlite3_finalize(s); }
};
using Db = std::unique_ptr<sqlite3, DbClose>;
using Stmt = std::unique_ptr<sqlite3_stmt, StmtFinalize>;

Db open_db(const std::string& file) {
  if (!fs::is_regular_file(file)) throw InputError(file, "ROS 2 bag file does not exist");
  sqlite3* raw = nullptr;
  const int rc = sqlite3_open_v2(file.c_str(), &raw, SQLITE_OPEN_READONLY, nullptr);
  Db db(raw);
  if (rc != SQLITE_OK) throw InputError(file, std::string("cannot open as SQLite: ") + sqlite3_errstr(rc));
  return db;
}

Stmt prepare(sqlite3* db, const std::string& file, const char* sql) {
  sqlite3_stmt* raw = nullptr;
  if (sqlite3_prepare_v2(db, sql, -1, &raw, nullptr) != SQLITE_OK) {
    throw InputError(file, std::string("not a rosbag2 sqlite3 file: ") + sqlite3_errmsg(db));
  }
  return Stmt(raw);
}

// Steps a statement: true with a row, false at the end; an error is an InputError naming the file.
bool step(sqlite3* db, sqlite3_stmt* s, const std::string& file) {
  const int rc = sqlite3_step(s);
  if (rc == SQLITE_ROW) return true;
  if (rc == SQLITE_DONE) return false;
  throw InputError(file, std::string("SQLite: ") + sqlite3_errmsg(db));
}

std::string text(sqlite3_stmt* s, int column) {
  const unsigned char* t = sqlite3_column_text(s, column);
  return t ? reinterpret_cast<const char*>(t) : "";
}

std::vector<std::uint8_t> blob(sqlite3_stmt* s, int column) {
  const auto* p = static_cast<const std::uint8_t*>(sqlite3_column_blob(s, column));
  const int n = sqlite3_column_bytes(s, column);
  return p ? std::vector<std::uint8_t>(p, p + n) : std::vector<std::uint8_t>{};
}

// The .db3 files of a bag folder, in metadata.yaml's order; a storage or compression vilslam cannot read is
// refused here.
std::vector<std::string> files_of_folder(const std::string& folder) {
  const fs::path metadata = fs::path(folder) / "metadata.yaml";
  YAML::Node info;
  try {
    info = YAML::LoadFile(metadata.string())["rosbag2_bagfile_information"];
  } catch (const YAML::Exception& e) {
    throw InputError(metadata.string(), std::string("cannot read: ") + e.what());
  }
  if (!info || !info.IsMap()) throw InputError(metadata.string(), "no rosbag2_bagfile_information section");
  const std::string storage = info["storage_identifier"] ? info["storage_identifier"].as<std::string>() : "";
  if (storage != "sqlite3") {
    throw InputError(metadata.string(), "storage '" + storage + "' is not supported, only sqlite3 (convert with "
                                        "`ros2 bag convert` and a storage_id: sqlite3 output)");
  }
  if (info["compression_format"] && !info["compression_format"].as<std::string>().empty()) {
    throw InputError(metadata.string(), "compressed bag (" + info["compression_format"].as<std::string>() +
                                            ") is not supported: decompress it with `ros2 bag convert`");
  }
  const YAML::Node paths = info["relative_file_paths"];
  if (!paths || !paths.IsSequence() || paths.size() == 0) throw InputError(metadata.string(), "no relative_file_paths");
  std::vector<std::string> files;
  for (const auto& p : paths) files.push_back((fs::path(folder) / p.as<std::string>()).string());
  return files;
}

}  // namespace

bool is_ros2_bag(const std::string& path) {
  const fs::path p(path);
  if (fs::is_directory(p)) return fs::exists(p / "metadata.yaml");
  return fs::is_regular_file(p) && p.extension() == ".db3";
}

std::unique_ptr<MessageLog> open_message_log(const std::string& path) {
  if (is_ros2_bag(path)) return std::make_unique<Ros2Bag>(path);
  return std::make_unique<BagIn>(path);
}

struct Ros2Bag::Impl {
  std::string path;
  std::vector<std::string> files;
  std::vector<Db> dbs;
  std::vector<BagTopic> topics;
  std::map<std::string, std::vector<std::int64_t>> topic_ids;  // topic -> its id in each file (-1: none)
  // topic -> (file, row id) of each message in log order, filled by the first for_each of the topic.
  mutable std::map<std::string, std::vector<std::pair<std::size_t, std::int64_t>>> rows;

  void visit_rows(const std::string& topic,
                  const std::function<void(std::size_t, std::int64_t, sqlite3_stmt*)>& visit) const {
    const auto ids = topic_ids.find(topic);
    if (ids == topic_ids.end()) throw InputError(path, "topic " + topic + " is not in the bag");
    for (std::size_t f = 0; f < files.size(); ++f) {
      if (ids->second[f] < 0) continue;
      Stmt s = prepare(dbs[f].get(), files[f],
                       "SELECT id, data FROM messages WHERE topic_id = ? ORDER BY timestamp, id");
      sqlite3_bind_int64(s.get(), 1, ids->second[f]);
      while (step(dbs[f].get(), s.get(), files[f])) visit(f, sqlite3_column_int64(s.get(), 0), s.get());
    }
  }
};

Ros2Bag::Ros2Bag(const std::string& path) : impl_(std::make_unique<Impl>()) {
  Impl& d = *impl_;
  d.path = path;
  d.files = fs::is_directory(path) ? files_of_folder(path) : std::vector<std::string>{path};
  std::map<std::string, BagTopic> by_name;
  for (std::size_t f = 0; f < d.files.size(); ++f) {
    const std::string& file = d.files[f];
    d.dbs.push_back(open_db(file));
    sqlite3* db = d.dbs.back().get();
    Stmt topics = prepare(db, file, "SELECT id, name, type, serialization_format FROM topics");
    while (step(db, topics.get(), file)) {
      const std::string name = text(topics.get(), 1), type = ros1_type_name(text(topics.get(), 2));
      const std::string format = text(topics.get(), 3);
      if (format != "cdr") throw InputError(file, "topic " + name + " is serialized as '" + format + "', not cdr");
      BagTopic& t = by_name[name];
      if (!t.datatype.empty() && t.datatype != type) {
        throw InputError(path, "topic " + name + " has messages of two types, " + t.datatype + " and " + type);
      }
      t.topic = name;
      t.datatype = type;
      t.md5sum = "*";
      auto& ids = d.topic_ids[name];
      ids.resize(d.files.size(), -1);
      ids[f] = sqlite3_column_int64(topics.get(), 0);
    }
    Stmt counts = prepare(db, file, "SELECT topic_id, COUNT(*) FROM messages GROUP BY topic_id");
    while (step(db, counts.get(), file)) {
      for (auto& [name, ids] : d.topic_ids) {
        if (ids[f] == sqlite3_column_int64(counts.get(), 0)) by_name[name].messages += sqlite3_column_int64(counts.get(), 1);
      }
    }
  }
  for (auto& [name, t] : by_name) d.topics.push_back(t);
}

Ros2Bag::~Ros2Bag() = default;

const std::string& Ros2Bag::path() const { return impl_->path; }
const std::vector<BagTopic>& Ros2Bag::topics() const { return impl_->topics; }

void Ros2Bag::for_each(const std::string& topic,
                       const std::function<void(std::size_t, const std::vector<std::uint8_t>&)>& visit) const {
  std::vector<std::pair<std::size_t, std::int64_t>> rows;
  impl_->visit_rows(topic, [&](std::size_t file, std::int64_t id, sqlite3_stmt* s) {
    rows.emplace_back(file, id);
    visit(rows.size() - 1, blob(s, 1));
  });
  impl_->rows[topic] = std::move(rows);
}

std::vector<std::uint8_t> Ros2Bag::message(const std::string& topic, std::size_t ordinal) {
  if (!impl_->rows.count(topic)) {
    auto& rows = impl_->rows[topic];
    impl_->visit_rows(topic, [&](std::size_t file, std::int64_t id, sqlite3_stmt*) { rows.emplace_back(file, id); });
  }
  const auto& rows = impl_->rows.at(topic);
  if (ordinal >= rows.size()) throw InputError(impl_->path, "topic " + topic + " has no message " + std::to_string(ordinal));
  const auto [file, id] = rows[ordinal];
  sqlite3* db = impl_->dbs[file].get();
  Stmt s = prepare(db, impl_->files[file], "SELECT data FROM messages WHERE id = ?");
  sqlite3_bind_int64(s.get(), 1, id);
  if (!step(db, s.get(), impl_->files[file])) {
    throw InputError(impl_->files[file], "message row " + std::to_string(id) + " of topic " + topic + " vanished");
  }
  return blob(s.get(), 0);
}

}  // namespace vilslam
