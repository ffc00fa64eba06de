// The tables of an EuRoC mav0 folder (io/euroc_tables.h); byte 0 picks the table.
#include <vector>

#include "entry_util.h"
#include "io/euroc_tables.h"

namespace vilslam::fuzz {

Outcome euroc_csv(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return kEmptyInput;
  const std::string path = write_temp_file("cam0/data.csv", data + 1, size - 1);
  return outcome_of([&] {
    switch (data[0] % 4) {
      case 0:
        read_imu_csv(path);
        break;
      case 1:
        read_groundtruth_csv(path, SE3());
        break;
      case 2:
        read_groundtruth_tum(path, SE3());
        break;
      default: {
        std::vector<std::string> problems;
        const std::vector<ImageRow> rows = read_camera_csv(path.substr(0, path.size() - 9), false, problems);
        pair_stereo(rows, rows, problems);
      }
    }
  });
}

}  // namespace vilslam::fuzz
