// KITTI odometry layout: DIR/{calib.txt, times.txt, image_0/, image_1/, velodyne/, [poses.txt]}.
// There is no IMU: the frame I is the rectified reference camera (cam0), so T_I_C0 is the identity
// (docs/formats.md derives the rest from P0, P1 and Tr).
#include <cstdio>
#include <filesystem>
#include <map>

#include "common/error.h"
#include "common/log.h"
#include "io/csv.h"
#include "io/dataset_index.h"
#include "io/yaml_util.h"

namespace vilslam {
namespace {

namespace fs = std::filesystem;

constexpr int kKittiLidarRings = 64;          // Velodyne HDL-64E
constexpr double kKittiLidarMaxRange_m = 120;

using Mat34 = Eigen::Matrix<double, 3, 4>;

Mat34 row_major_3x4(const Table& table, const TableRow& row, std::size_t first_col) {
  Mat34 M;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 4; ++c) M(r, c) = table.number(row, first_col + 4 * r + c);
  }
  return M;
}

// calib.txt rows "P0: 12 numbers", ..., "Tr: 12 numbers" by label.
std::map<std::string, Mat34> read_calib_txt(const std::string& path) {
  const Table table(path, ' ', 13);
  std::map<std::string, Mat34> matrices;
  for (const TableRow& row : table.rows()) {
    std::string label = table.text(row, 0);
    if (label.back() == ':') label.pop_back();
    matrices[label] = row_major_3x4(table, row, 1);
  }
  for (const char* needed : {"P0", "P1"}) {
    if (!matrices.count(needed)) throw InputError(path, std::string("missing ") + needed);
  }
  return matrices;
}

// P_i = K_i [I | t_i] projects rectified reference-camera points into camera i, so p_Ci = p_I + t_i
// with t_i = K_i^-1 P_i(:,3) (KITTI devkit readme), i.e. T_I_Ci = [I | -t_i].
CameraIntrinsics intrinsics_of(const Mat34& P, SE3& T_I_C, const std::string& path) {
  CameraIntrinsics cam;
  cam.fx = P(0, 0);
  cam.fy = P(1, 1);
  cam.cx = P(0, 2);
  cam.cy = P(1, 2);
  const Mat3 K = P.leftCols<3>();
  if (std::abs(K(0, 1)) > 1e-9 || K.row(2) != Eigen::RowVector3d(0, 0, 1) || std::abs(K(1, 0)) > 1e-9 ||
      cam.fx <= 0 || cam.fy <= 0) {
    throw InputError(path, "projection matrix is not of the rectified form K [I | t]");
  }
  T_I_C = SE3(Quat::Identity(), -(K.inverse() * P.col(3)));
  return cam;
}

std::vector<TimeNs> read_times(const std::string& path) {
  const Table table(path, ' ', 1);
  std::vector<TimeNs> times;
  for (const TableRow& row : table.rows()) times.push_back(table.seconds_as_ns(row, 0));
  table.require_increasing(times);
  return times;
}

std::vector<GroundTruthState> read_poses(const std::string& path, const std::vector<TimeNs>& times) {
  const Table table(path, ' ', 12);
  if (table.rows().size() != times.size()) {
    throw InputError(path, std::to_string(table.rows().size()) + " poses for " + std::to_string(times.size()) +
                               " times in times.txt");
  }
  std::vector<GroundTruthState> gt;
  for (std::size_t i = 0; i < times.size(); ++i) {
    const TableRow& row = table.rows()[i];
    const Mat34 M = row_major_3x4(table, row, 0);
    require_rotation(M.leftCols<3>(), "pose on line " + std::to_string(row.line), path);
    GroundTruthState s;
    s.t_ns = times[i];
    s.T_W_I = SE3(Mat3(M.leftCols<3>()), Vec3(M.col(3)));
    gt.push_back(s);
  }
  return gt;
}

std::string frame_file(const fs::path& dir, std::size_t i, const char* ext) {
  char name[32];
  std::snprintf(name, sizeof name, "%06zu%s", i, ext);
  return (dir / name).string();
}

// Frames whose files exist; a missing one is skipped and listed in problems.
bool present(const std::string& path, std::vector<std::string>& problems) {
  if (fs::exists(path)) return true;
  spdlog::warn("{}: missing, frame skipped", path);
  problems.push_back(path + ": missing, frame skipped");
  return false;
}

}  // namespace

DatasetIndex index_kitti(const std::string& root) {
  fs::path dir(root);
  if (!dir.has_filename()) dir = dir.parent_path();  // "seq/" names seq
  DatasetIndex index;
  index.summary.format = "kitti";
  index.summary.path = root;
  auto& problems = index.summary.problems;
  RigCalibration& calib = index.calibration;

  const std::string calib_path = (dir / "calib.txt").string();
  const auto P = read_calib_txt(calib_path);
  calib.cam0 = intrinsics_of(P.at("P0"), calib.T_I_C0, calib_path);
  calib.cam1 = intrinsics_of(P.at("P1"), calib.T_I_C1, calib_path);
  const std::vector<TimeNs> times = read_times((dir / "times.txt").string());

  const fs::path image_0 = dir / "image_0", image_1 = dir / "image_1", velodyne = dir / "velodyne";
  index.has_cameras = fs::is_directory(image_0) && fs::is_directory(image_1);
  if (index.has_cameras) {
    for (std::size_t i = 0; i < times.size(); ++i) {
      const std::string left = frame_file(image_0, i, ".png"), right = frame_file(image_1, i, ".png");
      if (present(left, problems) && present(right, problems)) index.stereo.push_back({times[i], left, right});
    }
    if (index.stereo.empty()) throw InputError(image_0.string(), "no images");
    const auto [width, height] = png_size(index.stereo.front().left_path);
    for (CameraIntrinsics* cam : {&calib.cam0, &calib.cam1}) {
      cam->width_px = width;
      cam->height_px = height;
    }
  }
  if (fs::is_directory(velodyne)) {
    if (!P.count("Tr")) throw InputError(calib_path, "missing Tr (velodyne to camera 0)");
    const Mat34& Tr = P.at("Tr");
    require_rotation(Tr.leftCols<3>(), "Tr", calib_path);
    calib.has_lidar = true;
    calib.T_I_L = SE3(Mat3(Tr.leftCols<3>()), Vec3(Tr.col(3)));
    calib.lidar.num_rings = kKittiLidarRings;
    calib.lidar.max_range_m = kKittiLidarMaxRange_m;
    index.scan_encoding = ScanEncoding::kKitti;
    for (std::size_t i = 0; i < times.size(); ++i) {
      const std::string bin = frame_file(velodyne, i, ".bin");
      if (present(bin, problems)) index.scans.push_back({times[i], bin, -1});
    }
  }
  if (times.size() >= 2) {
    const double rate_hz = static_cast<double>(times.size() - 1) * 1e9 / static_cast<double>(times.back() - times.front());
    calib.cam0.rate_hz = calib.cam1.rate_hz = calib.lidar.rate_hz = rate_hz;
  }
  if (index.has_cameras) validate_calibration(calib, calib_path);

  const fs::path standard_poses = dir.parent_path().parent_path() / "poses" / (dir.filename().string() + ".txt");
  for (const fs::path& poses : {dir / "poses.txt", standard_poses}) {
    if (fs::exists(poses)) {
      index.groundtruth = read_poses(poses.string(), times);
      break;
    }
  }
  return index;
}

}  // namespace vilslam
