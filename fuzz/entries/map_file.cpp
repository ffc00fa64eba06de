// A saved map folder (loop/map_file.h): byte 0 picks which of its four files the rest of the input replaces in
// a valid map, so each file is fuzzed with the other three consistent. A map that loads is also checked against
// its own rig and vocabulary identity.
#include <array>
#include <filesystem>

#include "entry_util.h"
#include "loop/map_file.h"

namespace vilslam::fuzz {
namespace {

namespace fs = std::filesystem;

constexpr std::array<const char*, 4> kFiles = {"map.yaml", "rig.yaml", "poses.tum", "key_frames.bin"};

// Three poses and one key frame with every kind of field (rows with and without a 3D point, BoW, features).
loop::SavedMap template_map() {
  loop::SavedMap map;
  map.rig = small_rig();
  for (int i = 0; i < 3; ++i) map.poses.push_back({1'000'000'000LL + i * 100'000'000LL, SE3(Quat::Identity(), Vec3(i, 0, 0))});
  loop::KeyFrame k;
  k.pose_index = 1;
  k.scan_t_ns = map.poses[1].t_ns;
  k.image.t_ns = k.scan_t_ns - 1'000'000;
  k.image.focal_px = 40.0;
  k.image.descriptors = cv::Mat(2, 32, CV_8U, cv::Scalar(7));
  k.image.left_norm = {{0.1, 0.2}, {-0.3, 0.0}};
  k.image.points_C0 = {Vec3(0.5, 1.0, 4.0), Vec3::Constant(std::nan(""))};
  k.image.bow = {{2, 0.5}, {9, 0.5}};
  k.features_L.edges = {{Vec3(1, 2, 3), 0.01f, 0.2f}};
  k.features_L.surfaces = {{Vec3(3, 2, 1), 0.02f, 0.001f}, {Vec3(4, 0, -1), 0.03f, 0.002f}};
  map.key_frames.push_back(k);
  map.vocabulary_id = 0x1234;
  return map;
}

// The template's folder, written once per process.
const fs::path& template_dir() {
  static const fs::path dir = [] {
    const fs::path d = fs::path(write_temp_file("template/unused", nullptr, 0)).parent_path() / "map";
    loop::save_map(d.string(), template_map());
    return d;
  }();
  return dir;
}

}  // namespace

Outcome map_file(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return kEmptyInput;
  const char* fuzzed = kFiles[data[0] % kFiles.size()];
  const fs::path dir = fs::path(write_temp_file(std::string("map/") + fuzzed, data + 1, size - 1)).parent_path();
  for (const char* file : kFiles) {
    if (file != fuzzed) fs::copy_file(template_dir() / file, dir / file, fs::copy_options::overwrite_existing);
  }
  return outcome_of([&] {
    const loop::SavedMap map = loop::load_map(dir.string());
    loop::check_map_fits(map, dir.string(), map.vocabulary_id, map.rig);
  });
}

}  // namespace vilslam::fuzz
