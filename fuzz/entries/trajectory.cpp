// Trajectory files (io/trajectory_io.h): byte 0 picks TUM, KITTI or EuRoC.
#include "entry_util.h"
#include "io/trajectory_io.h"

namespace vilslam::fuzz {

Outcome trajectory(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return kEmptyInput;
  const std::string path = write_temp_file("trajectory.txt", data + 1, size - 1);
  const TrajectoryFormat formats[] = {TrajectoryFormat::kTum, TrajectoryFormat::kKitti, TrajectoryFormat::kEuroc};
  return outcome_of([&] { read_trajectory(path, formats[data[0] % 3]); });
}

}  // namespace vilslam::fuzz
