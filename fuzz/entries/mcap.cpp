// ROS 2 bags in MCAP storage as datasets (io/mcap_file.h, io/dataset.h): the file is indexed and every event
// read, as `vilslam run` does, with a fixed small rig as its calibration (a bag carries none).
#include "entry_util.h"
#include "io/dataset.h"

namespace vilslam::fuzz {

Outcome mcap(const std::uint8_t* data, std::size_t size) {
  static DatasetOptions options;
  if (options.calibration_path.empty()) options.calibration_path = small_rig_yaml_file();
  const std::string path = write_temp_file("data.mcap", data, size);
  return outcome_of([&] {
    const auto reader = open_dataset(path, options);
    while (reader->next()) {
    }
  });
}

}  // namespace vilslam::fuzz
