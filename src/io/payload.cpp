// Loading and validating the payload files of an index (images, scans).
#include <opencv2/imgcodecs.hpp>

#include <array>
#include <cstdint>
#include <filesystem>
#include <fstream>

#include "common/error.h"
#include "io/dataset_index.h"
#include "io/scan_file.h"

namespace vilslam {
namespace {

cv::Mat load_grey(const std::string& path) {
  if (!std::filesystem::exists(path)) throw InputError(path, "image file is missing");
  cv::Mat image = cv::imread(path, cv::IMREAD_GRAYSCALE);
  if (image.empty()) throw InputError(path, "cannot decode image");
  return image;
}

std::uint32_t big_endian_u32(const unsigned char* p) {
  return (std::uint32_t{p[0]} << 24) | (std::uint32_t{p[1]} << 16) | (std::uint32_t{p[2]} << 8) | std::uint32_t{p[3]};
}

void check_size(const std::string& path, int width, int height, const CameraIntrinsics& cam) {
  if (cam.width_px > 0 && (width != cam.width_px || height != cam.height_px)) {
    throw InputError(path, "image is " + std::to_string(width) + "x" + std::to_string(height) +
                               ", the calibration says " + std::to_string(cam.width_px) + "x" +
                               std::to_string(cam.height_px));
  }
}

void check_point_count(const ScanEntry& entry, std::size_t num_points) {
  if (entry.num_points >= 0 && static_cast<std::size_t>(entry.num_points) != num_points) {
    throw InputError(entry.path, "has " + std::to_string(num_points) + " points, the index lists " +
                                     std::to_string(entry.num_points));
  }
}

}  // namespace

// PNG structure (ISO/IEC 15948): 8-byte signature, IHDR first (length 13), IEND last (12 bytes).
// Returns (width, height).
std::pair<int, int> png_size(const std::string& path) {
  static const unsigned char kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  static const unsigned char kIend[12] = {0, 0, 0, 0, 'I', 'E', 'N', 'D', 0xae, 0x42, 0x60, 0x82};
  std::ifstream f(path, std::ios::binary);
  if (!f) throw InputError(path, "image file is missing");
  std::array<unsigned char, 24> head{};
  f.read(reinterpret_cast<char*>(head.data()), head.size());
  if (!f || !std::equal(kSignature, kSignature + 8, head.begin())) throw InputError(path, "not a PNG file (bad signature)");
  if (big_endian_u32(head.data() + 8) != 13 || std::string(head.begin() + 12, head.begin() + 16) != "IHDR") {
    throw InputError(path, "corrupt PNG: IHDR chunk missing");
  }
  const auto width = big_endian_u32(head.data() + 16);
  const auto height = big_endian_u32(head.data() + 20);
  if (width == 0 || height == 0 || width > (1u << 16) || height > (1u << 16)) {
    throw InputError(path, "corrupt PNG: image size " + std::to_string(width) + "x" + std::to_string(height));
  }
  std::array<unsigned char, 12> tail{};
  f.seekg(-12, std::ios::end);
  f.read(reinterpret_cast<char*>(tail.data()), tail.size());
  if (!f || !std::equal(kIend, kIend + 12, tail.begin())) throw InputError(path, "corrupt PNG: truncated (no IEND chunk)");
  return {static_cast<int>(width), static_cast<int>(height)};
}

StereoFrame load_stereo(const StereoEntry& entry) {
  StereoFrame frame;
  frame.t_ns = entry.t_ns;
  frame.left = load_grey(entry.left_path);
  frame.right = load_grey(entry.right_path);
  return frame;
}

LidarScan load_scan(const ScanEntry& entry, ScanEncoding encoding) {
  LidarScan scan = encoding == ScanEncoding::kVilslam ? read_scan_file(entry.path) : read_kitti_scan(entry.path);
  check_point_count(entry, scan.points.size());
  scan.t_ns = entry.t_ns;
  return scan;
}

StereoFrame load_stereo(const DatasetIndex& index, std::size_t i) {
  return index.store ? index.store->stereo(i) : load_stereo(index.stereo[i]);
}

LidarScan load_scan(const DatasetIndex& index, std::size_t i) {
  return index.store ? index.store->scan(i) : load_scan(index.scans[i], index.scan_encoding);
}

void check_payloads(const DatasetIndex& index, bool deep) {
  const RigCalibration& calib = index.calibration;
  if (index.store && !deep) return;
  for (std::size_t i = 0; i < index.stereo.size(); ++i) {
    const StereoEntry& e = index.stereo[i];
    if (deep) {
      const StereoFrame f = load_stereo(index, i);
      check_size(e.left_path, f.left.cols, f.left.rows, calib.cam0);
      check_size(e.right_path, f.right.cols, f.right.rows, calib.cam1);
    } else {
      const auto [w0, h0] = png_size(e.left_path);
      check_size(e.left_path, w0, h0, calib.cam0);
      const auto [w1, h1] = png_size(e.right_path);
      check_size(e.right_path, w1, h1, calib.cam1);
    }
  }
  for (std::size_t i = 0; i < index.scans.size(); ++i) {
    const ScanEntry& e = index.scans[i];
    if (deep) {
      load_scan(index, i);
    } else {
      check_point_count(e, index.scan_encoding == ScanEncoding::kVilslam ? check_scan_file(e.path)
                                                                          : check_kitti_scan(e.path));
    }
  }
}

}  // namespace vilslam
