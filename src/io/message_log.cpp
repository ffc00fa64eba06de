#include "io/message_log.h"

#include <yaml-cpp/yaml.h>

#include <filesystem>

#include "common/error.h"
#include "io/mcap_file.h"
#include "io/ros2_bag_file.h"
#include "io/rosbag_file.h"

namespace vilslam {
namespace {

namespace fs = std::filesystem;

struct Ros2Files {
  std::string storage;  // sqlite3 or mcap
  std::vector<std::string> files;
};

// A ROS 2 bag folder's storage and files from its metadata.yaml; a compressed bag is refused here.
Ros2Files files_of_folder(const std::string& folder) {
  const fs::path metadata = fs::path(folder) / "metadata.yaml";
  YAML::Node info;
  try {
    info = YAML::LoadFile(metadata.string())["rosbag2_bagfile_information"];
  } catch (const YAML::Exception& e) {
    throw InputError(metadata.string(), std::string("cannot read: ") + e.what());
  }
  if (!info || !info.IsMap()) throw InputError(metadata.string(), "no rosbag2_bagfile_information section");
  Ros2Files out;
  out.storage = info["storage_identifier"] ? info["storage_identifier"].as<std::string>() : "";
  if (out.storage != "sqlite3" && out.storage != "mcap") {
    throw InputError(metadata.string(), "storage '" + out.storage + "' is not supported (sqlite3, mcap)");
  }
  if (info["compression_format"] && !info["compression_format"].as<std::string>().empty()) {
    throw InputError(metadata.string(), "compressed bag (" + info["compression_format"].as<std::string>() +
                                            ") is not supported: decompress it with `ros2 bag convert`");
  }
  const YAML::Node paths = info["relative_file_paths"];
  if (!paths || !paths.IsSequence() || paths.size() == 0) throw InputError(metadata.string(), "no relative_file_paths");
  for (const auto& p : paths) out.files.push_back((fs::path(folder) / p.as<std::string>()).string());
  return out;
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

void IndexedLog::for_each(const std::string& topic,
                          const std::function<void(std::size_t, const std::vector<std::uint8_t>&)>& visit) const {
  const std::vector<std::size_t>& ids = ids_of(topic);
  for (std::size_t k = 0; k < ids.size(); ++k) visit(k, fetch_(ids[k]));
}

std::vector<std::uint8_t> IndexedLog::message(const std::string& topic, std::size_t ordinal) {
  const std::vector<std::size_t>& ids = ids_of(topic);
  if (ordinal >= ids.size()) throw InputError(path_, "topic " + topic + " has no message " + std::to_string(ordinal));
  return fetch_(ids[ordinal]);
}

bool is_ros2_bag(const std::string& path) {
  const fs::path p(path);
  if (fs::is_directory(p)) return fs::exists(p / "metadata.yaml");
  return fs::is_regular_file(p) && (p.extension() == ".db3" || p.extension() == ".mcap");
}

std::unique_ptr<MessageLog> open_message_log(const std::string& path) {
  if (!is_ros2_bag(path)) return std::make_unique<BagIn>(path);
  const Ros2Files bag = fs::is_directory(path)
                            ? files_of_folder(path)
                            : Ros2Files{fs::path(path).extension() == ".mcap" ? "mcap" : "sqlite3", {path}};
  if (bag.storage == "mcap") return open_mcap_bag(path, bag.files);
  return open_sqlite_bag(path, bag.files);
}

}  // namespace vilslam
