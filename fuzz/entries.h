#pragma once
// The fuzz targets' entry points (docs/fuzzing.md). Each feeds one input to one reader of outside data and
// says how the reader ended: it read the input, or it rejected it with the project's InputError (or, for
// the ROS message decoders, the documented WireError). Anything else escaping an entry, a crash, a
// sanitizer report or a hang is a finding. libfuzzer_main.cpp makes one libFuzzer binary per entry; the
// regression test (tests/fuzz) runs the kept inputs of past findings through the same entries.
#include <cstddef>
#include <cstdint>
#include <string>

namespace vilslam::fuzz {

struct Outcome {
  bool read = false;
  std::string error;  // the InputError's (WireError's) message when the reader rejected the input
};

using Entry = Outcome (*)(const std::uint8_t* data, std::size_t size);

// Targets whose first input byte picks one of several readers say so; the rest of the input is the file.
Outcome euroc_csv(const std::uint8_t* data, std::size_t size);         // byte 0: imu, gt csv, gt tum, camera csv
Outcome calibration_yaml(const std::uint8_t* data, std::size_t size);  // byte 0: rig, EuRoC sensor.yaml, Kalibr
Outcome run_config(const std::uint8_t* data, std::size_t size);
Outcome cloud_pcd(const std::uint8_t* data, std::size_t size);
Outcome cloud_ply(const std::uint8_t* data, std::size_t size);
Outcome scan_bin(const std::uint8_t* data, std::size_t size);    // byte 0: KITTI .bin, the project's scan .bin
Outcome trajectory(const std::uint8_t* data, std::size_t size);  // byte 0: TUM, KITTI, EuRoC
Outcome loops_csv(const std::uint8_t* data, std::size_t size);
Outcome vocabulary(const std::uint8_t* data, std::size_t size);
Outcome ros_messages(const std::uint8_t* data, std::size_t size);  // byte 0: message type, ROS1 or CDR
Outcome rosbag(const std::uint8_t* data, std::size_t size);
Outcome mcap(const std::uint8_t* data, std::size_t size);
Outcome map_file(const std::uint8_t* data, std::size_t size);  // byte 0: which file of a saved map

// The entry of a target by name (the test's table); nullptr for an unknown name.
Entry find_entry(const char* name);

}  // namespace vilslam::fuzz
