#pragma once
// What the entries share: the outcome of a read, and the fuzz input as a file for readers that take a path.
#include <cstddef>
#include <cstdint>
#include <string>

#include "common/calibration.h"
#include "common/error.h"
#include "entries.h"

namespace vilslam::fuzz {

// Read when read() returns, rejected when it throws InputError; anything else propagates (a finding).
template <typename Read>
Outcome outcome_of(Read&& read) {
  try {
    read();
    return {true, {}};
  } catch (const InputError& e) {
    return {false, e.what()};
  }
}

// Targets whose first byte picks the reader have nothing to read in an empty input.
inline const Outcome kEmptyInput{false, "empty input"};

// The path of `name` (may hold folders) in this process's own temporary folder (under $TMPDIR; scripts/fuzz
// points it at /dev/shm), holding exactly the given bytes. The folder is removed at exit.
std::string write_temp_file(const std::string& name, const std::uint8_t* data, std::size_t size);

// A valid rig with tiny cameras and a LiDAR, for targets that need one beside the fuzzed file.
RigCalibration small_rig();
// small_rig() as a rig YAML in the temporary folder (written once per process), for the bag targets.
std::string small_rig_yaml_file();

}  // namespace vilslam::fuzz
