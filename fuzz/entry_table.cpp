#include <cstring>

#include "entries.h"

namespace vilslam::fuzz {

Entry find_entry(const char* name) {
  static const struct {
    const char* name;
    Entry entry;
  } kEntries[] = {{"euroc_csv", euroc_csv},   {"calibration_yaml", calibration_yaml},
                  {"run_config", run_config}, {"cloud_pcd", cloud_pcd},
                  {"cloud_ply", cloud_ply},   {"scan_bin", scan_bin},
                  {"trajectory", trajectory}, {"loops_csv", loops_csv},
                  {"vocabulary", vocabulary}, {"ros_messages", ros_messages},
                  {"rosbag", rosbag},         {"map_file", map_file},
                  {"mcap", mcap}};
  for (const auto& e : kEntries) {
    if (std::strcmp(e.name, name) == 0) return e.entry;
  }
  return nullptr;
}

}  // namespace vilslam::fuzz
