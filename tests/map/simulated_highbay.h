#pragma once
// `simulate highbay --preview --seed 3 --ideal-sensors`, simulated once for all the test processes, and its ground-truth
// LiDAR poses. Ideal sensors: the map tests measure maps built from the true poses against the world, and
// with realism the LiDAR's true mount is 0.5 deg / 1 cm off the nominal T_I_L these poses go through.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "io/dataset.h"
#include "shared_simulation.h"
#include "test_util.h"

namespace vilslam::test {

constexpr std::uint64_t kHighbaySeed = 3;

// Path of the simulated dataset ("" after a failure, which is reported); shared by the test processes.
inline const std::string& highbay_preview() {
  static const std::string path =
      shared_simulation("highbay --preview --seed " + std::to_string(kHighbaySeed) + " --ideal-sensors");
  return path;
}

// T_W_L = T_W_I T_I_L at every ground-truth state.
inline Trajectory groundtruth_lidar_poses(const std::string& dataset) {
  const auto reader = open_dataset(dataset);
  Trajectory T_W_L;
  for (const GroundTruthState& g : reader->groundtruth()) T_W_L.push_back({g.t_ns, g.T_W_I * reader->calibration().T_I_L});
  return T_W_L;
}

}  // namespace vilslam::test
