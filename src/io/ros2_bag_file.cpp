#include "io/ros2_bag_file.h"

#include <sqlite3.h>

#include <filesystem>
#include <map>

#include "common/error.h"
#include "io/ros2_messages.h"  // ros1_type_name

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

}  // namespace

std::unique_ptr<IndexedLog> open_sqlite_bag(const std::string& path, const std::vector<std::string>& files) {
  struct Storage {
    std::vector<std::string> files;
    std::vector<Db> dbs;
    std::vector<std::pair<std::size_t, std::int64_t>> rows;  // (file, row id) of each message
  };
  auto storage = std::make_shared<Storage>();
  storage->files = files;
  std::map<std::string, BagTopic> by_name;
  std::map<std::string, std::vector<std::size_t>> ids;
  for (std::size_t f = 0; f < files.size(); ++f) {
    const std::string& file = files[f];
    storage->dbs.push_back(open_db(file));
    sqlite3* db = storage->dbs.back().get();
    std::map<std::int64_t, std::string> topic_of;  // this file's topic ids
    Stmt topics = prepare(db, file, "SELECT id, name, type, serialization_format FROM topics");
    while (step(db, topics.get(), file)) {
      const std::string name = text(topics.get(), 1), type = ros1_type_name(text(topics.get(), 2));
      const std::string format = text(topics.get(), 3);
      if (format != "cdr") throw InputError(file, "topic " + name + " is serialized as '" + format + "', not cdr");
      BagTopic& t = by_name[name];
      if (!t.datatype.empty() && t.datatype != type) {
        throw InputError(path, "topic " + name + " has messages of two types, " + t.datatype + " and " + type);
      }
      t = {name, type, "*", t.messages};
      topic_of[sqlite3_column_int64(topics.get(), 0)] = name;
    }
    Stmt messages = prepare(db, file, "SELECT id, topic_id FROM messages ORDER BY timestamp, id");
    while (step(db, messages.get(), file)) {
      const auto topic = topic_of.find(sqlite3_column_int64(messages.get(), 1));
      if (topic == topic_of.end()) {
        throw InputError(file, "message row " + std::to_string(sqlite3_column_int64(messages.get(), 0)) + " has an unknown topic id");
      }
      ++by_name[topic->second].messages;
      ids[topic->second].push_back(storage->rows.size());
      storage->rows.emplace_back(f, sqlite3_column_int64(messages.get(), 0));
    }
  }
  std::vector<BagTopic> topics;
  for (auto& [name, t] : by_name) topics.push_back(t);
  return std::make_unique<IndexedLog>(path, std::move(topics), std::move(ids), [storage](std::size_t id) {
    const auto [f, row] = storage->rows[id];
    sqlite3* db = storage->dbs[f].get();
    Stmt s = prepare(db, storage->files[f], "SELECT data FROM messages WHERE id = ?");
    sqlite3_bind_int64(s.get(), 1, row);
    if (!step(db, s.get(), storage->files[f])) throw InputError(storage->files[f], "message row " + std::to_string(row) + " vanished");
    return blob(s.get(), 0);
  });
}

}  // namespace vilslam
