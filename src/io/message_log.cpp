#include "io/message_log.h"

#include <yaml-cpp/yaml.h>

#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <filesystem>

#include "common/error.h"
#include "io/mcap_file.h"
#include "io/ros2_bag_file.h"
#include "io/rosbag_file.h"
#include "io/ros_wire.h"
#include "io/zstd_util.h"

namespace vilslam {
namespace {

namespace fs = std::filesystem;

constexpr std::size_t kMaxMessageBytes = std::size_t{1} << 30;  // a larger decompressed message is corrupt

struct Ros2Files {
  std::string storage;  // sqlite3 or mcap
  std::vector<std::string> files;
  std::string compression_mode;  // "" (none), FILE or MESSAGE (zstd)
};

// A ROS 2 bag folder's storage, files and compression from its metadata.yaml.
Ros2Files files_of_folder(const std::string& folder) {
  const fs::path metadata = fs::path(folder) / "metadata.yaml";
  YAML::Node info;
  try {
    info = YAML::LoadFile(metadata.string())["rosbag2_bagfile_information"];
  } catch (const YAML::Exception& e) {
    throw InputError(metadata.string(), std::string("cannot read: ") + e.what());
  }
  if (!info || !info.IsMap()) throw InputError(metadata.string(), "no rosbag2_bagfile_information section");
  const auto text = [&](const char* key) { return info[key] && info[key].IsScalar() ? info[key].Scalar() : std::string(); };
  Ros2Files out;
  out.storage = text("storage_identifier");
  if (out.storage != "sqlite3" && out.storage != "mcap") {
    throw InputError(metadata.string(), "storage '" + out.storage + "' is not supported (sqlite3, mcap)");
  }
  const std::string format = text("compression_format");
  if (!format.empty()) {
    out.compression_mode = text("compression_mode");
    std::transform(out.compression_mode.begin(), out.compression_mode.end(), out.compression_mode.begin(), ::toupper);
    if (format != "zstd" || (out.compression_mode != "FILE" && out.compression_mode != "MESSAGE")) {
      throw InputError(metadata.string(), "compression '" + format + "' by '" + text("compression_mode") +
                                              "' is not supported (zstd by FILE or MESSAGE)");
    }
  }
  const YAML::Node paths = info["relative_file_paths"];
  if (!paths || !paths.IsSequence() || paths.size() == 0) throw InputError(metadata.string(), "no relative_file_paths");
  for (const auto& p : paths) out.files.push_back((fs::path(folder) / p.as<std::string>()).string());
  return out;
}

// A folder of this process's, removed with everything in it when the last owner lets go.
struct TempFolder {
  fs::path path;
  TempFolder() {
    static int count = 0;
    path = fs::temp_directory_path() / ("vilslam-bag-" + std::to_string(::getpid()) + "-" + std::to_string(count++));
    fs::create_directories(path);
  }
  ~TempFolder() {
    std::error_code ignored;
    fs::remove_all(path, ignored);
  }
};

// compression_mode FILE: each file is one zstd stream of the storage file; they are decompressed into a
// temporary folder, which the log keeps.
std::shared_ptr<TempFolder> decompress_files(std::vector<std::string>& files) {
  auto folder = std::make_shared<TempFolder>();
  for (std::string& file : files) {
    const fs::path stored(file);
    const fs::path plain = folder->path / stored.stem();  // name.db3.zstd -> name.db3
    try {
      zstd_decompress_file(file, plain.string());
    } catch (const WireError& e) {
      throw InputError(file, e.what());
    }
    file = plain.string();
  }
  return folder;
}

}  // namespace

IndexedLog::IndexedLog(std::string path, std::vector<BagTopic> topics, std::map<std::string, std::vector<std::size_t>> ids,
                       Fetch fetch)
    : path_(std::move(path)), topics_(std::move(topics)), ids_(std::move(ids)), fetch_(std::move(fetch)) {}

const std::vector<std::size_t>& IndexedLog::ids_of(const std::string& topic) const {
  static const std::vector<std::size_t> none;
  const auto it = ids_.find(topic);
  return it == ids_.end() ? none : it->second;
}

std::vector<std::uint8_t> IndexedLog::fetch(std::size_t id) const {
  std::vector<std::uint8_t> bytes = fetch_(id);
  if (!zstd_messages_) return bytes;
  try {
    return zstd_decompress(bytes.data(), bytes.size(), kMaxMessageBytes);
  } catch (const WireError& e) {
    throw InputError(path_, std::string("compressed message: ") + e.what());
  }
}

void IndexedLog::for_each(const std::string& topic,
                          const std::function<void(std::size_t, const std::vector<std::uint8_t>&)>& visit) const {
  const std::vector<std::size_t>& ids = ids_of(topic);
  for (std::size_t k = 0; k < ids.size(); ++k) visit(k, fetch(ids[k]));
}

std::vector<std::uint8_t> IndexedLog::message(const std::string& topic, std::size_t ordinal) {
  const std::vector<std::size_t>& ids = ids_of(topic);
  if (ordinal >= ids.size()) throw InputError(path_, "topic " + topic + " has no message " + std::to_string(ordinal));
  return fetch(ids[ordinal]);
}

bool is_ros2_bag(const std::string& path) {
  const fs::path p(path);
  if (fs::is_directory(p)) return fs::exists(p / "metadata.yaml");
  return fs::is_regular_file(p) && (p.extension() == ".db3" || p.extension() == ".mcap");
}

std::unique_ptr<MessageLog> open_message_log(const std::string& path) {
  if (!is_ros2_bag(path)) return std::make_unique<BagIn>(path);
  Ros2Files bag = fs::is_directory(path) ? files_of_folder(path)
                                         : Ros2Files{fs::path(path).extension() == ".mcap" ? "mcap" : "sqlite3", {path}, ""};
  std::shared_ptr<TempFolder> decompressed;
  if (bag.compression_mode == "FILE") decompressed = decompress_files(bag.files);
  std::unique_ptr<IndexedLog> log = bag.storage == "mcap" ? open_mcap_bag(path, bag.files) : open_sqlite_bag(path, bag.files);
  if (decompressed) log->keep(decompressed);
  if (bag.compression_mode == "MESSAGE") log->decompress_messages();
  return log;
}

}  // namespace vilslam
