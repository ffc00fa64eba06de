#pragma once
// A saved map: what re-localization in a later run needs (docs/formats.md, "Map files"). A folder holding
//   map.yaml        format name and version, the vocabulary's identity, counts
//   rig.yaml        the rig calibration the map was built with (io/calibration_io.h)
//   poses.tum       every LiDAR pose T_W_L of the optimized global pose graph, in graph order
//   key_frames.bin  the key frames: key image (ORB rows, normalized coordinates, 3D points, BoW) and key scan
//                   (dewarped features in L), each with the index of its pose in poses.tum
#include <cstdint>
#include <string>
#include <vector>

#include "common/calibration.h"
#include "common/types.h"
#include "loop/key_frame.h"

namespace vilslam::loop {

struct SavedMap {
  RigCalibration rig;
  Trajectory poses;                  // T_W_L of the global graph; key frames index into it
  std::vector<KeyFrame> key_frames;  // in time order
  std::uint64_t vocabulary_id = 0;   // vocabulary_identity() of the vocabulary their BoW vectors come from
};

// FNV-1a (64 bit) of the file's bytes: two vocabularies with the same words have the same identity.
// Throws InputError naming the file when it cannot be read.
std::uint64_t vocabulary_identity(const std::string& vocabulary_path);

// Writes the folder atomically (<dir>.partial, then renamed; an existing dir is replaced). Throws
// std::invalid_argument when a key frame's pose index is outside the poses.
void save_map(const std::string& dir, const SavedMap& map);

// Throws InputError naming the file and the problem: a missing file, another format or version, a truncated
// file or trailing bytes, a non-finite value, a key frame whose pose index is out of range or whose time is
// not its pose's, key frames out of time order.
SavedMap load_map(const std::string& dir);

// Throws InputError naming <dir>/map.yaml when the map's BoW vectors come from another vocabulary, or
// <dir>/rig.yaml when the map's rig is not this one (another image size, intrinsics more than 0.5 px apart,
// extrinsics more than 1 mm or 0.1 degree apart, a LiDAR on one rig only).
void check_map_fits(const SavedMap& map, const std::string& dir, std::uint64_t vocabulary_id, const RigCalibration& rig);

}  // namespace vilslam::loop
