#include "entry_util.h"

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "io/calibration_io.h"

namespace vilslam::fuzz {
namespace {

namespace fs = std::filesystem;

struct ProcessFolder {
  fs::path path = fs::temp_directory_path() / ("vilslam_fuzz_" + std::to_string(::getpid()));
  ProcessFolder() { fs::create_directories(path); }
  ~ProcessFolder() {
    std::error_code ignored;
    fs::remove_all(path, ignored);
  }
};

}  // namespace

std::string write_temp_file(const std::string& name, const std::uint8_t* data, std::size_t size) {
  static const ProcessFolder folder;
  const fs::path path = folder.path / name;
  fs::create_directories(path.parent_path());
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  if (!out.flush()) throw std::runtime_error("cannot write " + path.string());
  return path.string();
}

RigCalibration small_rig() {
  RigCalibration c;
  for (CameraIntrinsics* cam : {&c.cam0, &c.cam1}) {
    cam->width_px = 8;
    cam->height_px = 6;
    cam->fx = cam->fy = 10;
    cam->cx = 4;
    cam->cy = 3;
    cam->rate_hz = 20;
  }
  c.has_lidar = true;
  return c;
}

std::string small_rig_yaml_file() {
  static const std::string path = [] {
    const std::string text = rig_yaml_text(small_rig());
    return write_temp_file("rig.yaml", reinterpret_cast<const std::uint8_t*>(text.data()), text.size());
  }();
  return path;
}

}  // namespace vilslam::fuzz
