// LiDAR scan payloads (io/scan_file.h): byte 0 picks a KITTI velodyne .bin or the project's scan .bin.
#include "entry_util.h"
#include "io/scan_file.h"

namespace vilslam::fuzz {

Outcome scan_bin(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return kEmptyInput;
  const std::string path = write_temp_file("scan.bin", data + 1, size - 1);
  return outcome_of([&] {
    if (data[0] % 2 == 0) {
      check_kitti_scan(path);
      read_kitti_scan(path);
    } else {
      check_scan_file(path);
      read_scan_file(path);
    }
  });
}

}  // namespace vilslam::fuzz
