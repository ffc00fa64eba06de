// The project's folder format (docs/formats.md): EuRoC ASL plus rig.yaml, mav0/lidar0 and model.ply.
// Unlike EuRoC, every listed payload must exist (the writer guarantees completeness).
#include <filesystem>

#include "common/error.h"
#include "io/calibration_io.h"
#include "io/csv.h"
#include "io/dataset_index.h"
#include "io/euroc_calibration.h"
#include "io/euroc_tables.h"

namespace vilslam {
namespace {

namespace fs = std::filesystem;

// Calibration from the EuRoC-style sensor.yaml files when there is no rig.yaml.
RigCalibration calibration_from_sensor_yamls(const fs::path& mav0) {
  RigCalibration calib;
  const EurocImu imu = read_euroc_imu_yaml((mav0 / "imu0" / "sensor.yaml").string());
  calib.imu = imu.noise;
  read_euroc_cameras(mav0.string(), imu.T_B_I, calib);
  const fs::path lidar_yaml = mav0 / "lidar0" / "sensor.yaml";
  if (fs::exists(lidar_yaml)) {
    const EurocLidar lidar = read_euroc_lidar_yaml(lidar_yaml.string());
    calib.has_lidar = true;
    calib.lidar = lidar.intrinsics;
    calib.T_I_L = imu.T_B_I.inverse() * lidar.T_B_L;
  }
  validate_calibration(calib, mav0.string());
  return calib;
}

std::vector<ScanEntry> read_lidar_csv(const fs::path& lidar_dir) {
  const std::string csv = (lidar_dir / "data.csv").string();
  const Table table(csv, ',', 3);
  std::vector<ScanEntry> scans;
  for (const TableRow& row : table.rows()) {
    ScanEntry e;
    e.t_ns = table.time_ns(row, 0);
    e.path = (lidar_dir / "data" / table.text(row, 1)).string();
    e.num_points = table.integer(row, 2);
    if (e.num_points < 0) throw InputError(csv, "negative num_points", row.line);
    if (!fs::exists(e.path)) throw InputError(e.path, "scan listed in " + csv + ":" + std::to_string(row.line) + " is missing");
    scans.push_back(e);
  }
  table.require_increasing(times_of(scans));
  return scans;
}

}  // namespace

DatasetIndex index_vilslam(const std::string& root) {
  const fs::path dir(root);
  const fs::path mav0 = dir / "mav0";
  if (!fs::is_directory(mav0)) throw InputError(root, "no mav0/ folder");
  DatasetIndex index;
  index.summary.format = "vilslam";
  index.summary.path = root;
  const fs::path rig = dir / "rig.yaml";
  index.calibration = fs::exists(rig) ? read_rig_yaml(rig.string()) : calibration_from_sensor_yamls(mav0);
  const bool lidar_folder = fs::is_directory(mav0 / "lidar0");
  if (lidar_folder && !index.calibration.has_lidar) {
    throw InputError(rig.string(), "mav0/lidar0 exists but the calibration has no lidar section");
  }

  const fs::path imu_csv = mav0 / "imu0" / "data.csv";
  if (!fs::exists(imu_csv)) throw InputError(imu_csv.string(), "missing");
  index.imu = read_imu_csv(imu_csv.string());

  if (fs::is_directory(mav0 / "cam0") || fs::is_directory(mav0 / "cam1")) {
    index.has_cameras = true;
    auto& problems = index.summary.problems;
    const auto left = read_camera_csv((mav0 / "cam0").string(), true, problems);
    const auto right = read_camera_csv((mav0 / "cam1").string(), true, problems);
    index.stereo = pair_stereo(left, right, problems);
  }
  if (lidar_folder) index.scans = read_lidar_csv(mav0 / "lidar0");
  index.scan_encoding = ScanEncoding::kVilslam;
  index.groundtruth = read_euroc_groundtruth(mav0.string(), SE3::identity());
  if (fs::exists(dir / "model.ply")) index.reference_model_path = (dir / "model.ply").string();
  return index;
}

}  // namespace vilslam
