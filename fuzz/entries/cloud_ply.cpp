// PLY clouds, ASCII and binary (io/cloud_io.h).
#include "entry_util.h"
#include "io/cloud_io.h"

namespace vilslam::fuzz {

Outcome cloud_ply(const std::uint8_t* data, std::size_t size) {
  const std::string path = write_temp_file("cloud.ply", data, size);
  return outcome_of([&] { read_cloud(path); });
}

}  // namespace vilslam::fuzz
