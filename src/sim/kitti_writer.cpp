#include "sim/kitti_writer.h"

#include <cstdio>
#include <filesystem>
#include <fstream>

#include "common/error.h"

namespace vilslam::sim {
namespace {

namespace fs = std::filesystem;

std::string row_3x4(const Mat4& T) {
  std::string out;
  char buf[32];
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 4; ++c) {
      std::snprintf(buf, sizeof buf, "%s%.9e", out.empty() ? "" : " ", T(r, c));
      out += buf;
    }
  return out;
}

// Pinhole projection of a rectified camera displaced by tx_m along x (KITTI P matrices).
Mat4 projection(const CameraIntrinsics& cam, double tx_m) {
  Mat4 P = Mat4::Zero();
  P(0, 0) = cam.fx;
  P(0, 2) = cam.cx;
  P(0, 3) = -cam.fx * tx_m;
  P(1, 1) = cam.fy;
  P(1, 2) = cam.cy;
  P(2, 2) = 1;
  return P;
}

void write_text(const fs::path& path, const std::string& text) {
  std::ofstream out(path, std::ios::trunc);
  out << text;
  out.close();
  if (!out) throw InputError(path.string(), "cannot write file");
}

}  // namespace

KittiWriter::KittiWriter(std::string dir, const RigCalibration& calib) : dir_(std::move(dir)), calib_(calib) {
  std::error_code ec;
  fs::create_directories(fs::path(dir_) / "velodyne", ec);
  if (ec) throw InputError(dir_, "cannot create folder: " + ec.message());
}

void KittiWriter::add_scan(const LidarScan& scan, const SE3& T_W_L) {
  char name[32];
  std::snprintf(name, sizeof name, "%06zu.bin", times_ns_.size());
  std::vector<float> records;
  records.reserve(4 * scan.points.size());
  for (const LidarPoint& p : scan.points) records.insert(records.end(), {p.x, p.y, p.z, p.intensity});
  const fs::path path = fs::path(dir_) / "velodyne" / name;
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(records.data()), static_cast<std::streamsize>(records.size() * sizeof(float)));
  out.close();
  if (!out) throw InputError(path.string(), "cannot write file");
  times_ns_.push_back(scan.t_ns);
  poses_W_L_.push_back(T_W_L);
}

void KittiWriter::finish() const {
  std::string times, poses;
  char buf[64];
  for (std::size_t k = 0; k < times_ns_.size(); ++k) {
    std::snprintf(buf, sizeof buf, "%.6e\n", ns_to_s(times_ns_[k] - times_ns_.front()));
    times += buf;
    poses += row_3x4((poses_W_L_.front().inverse() * poses_W_L_[k]).matrix()) + "\n";
  }
  write_text(fs::path(dir_) / "times.txt", times);
  write_text(fs::path(dir_) / "poses.txt", poses);
  const double baseline_m = calib_.T_C0_C1().translation().norm();
  const Mat4 P0 = projection(calib_.cam0, 0), P1 = projection(calib_.cam1, baseline_m);
  write_text(fs::path(dir_) / "calib.txt", "P0: " + row_3x4(P0) + "\nP1: " + row_3x4(P1) + "\nP2: " + row_3x4(P0) +
                                               "\nP3: " + row_3x4(P1) + "\nTr: " + row_3x4(Mat4::Identity()) +
                                               "\n");
}

}  // namespace vilslam::sim
