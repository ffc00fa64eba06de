// PCD clouds, ASCII, binary and PCL binary_compressed (io/cloud_io.h).
#include "entry_util.h"
#include "io/cloud_io.h"

namespace vilslam::fuzz {

Outcome cloud_pcd(const std::uint8_t* data, std::size_t size) {
  const std::string path = write_temp_file("cloud.pcd", data, size);
  return outcome_of([&] { read_cloud(path); });
}

}  // namespace vilslam::fuzz
