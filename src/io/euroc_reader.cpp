// EuRoC ASL layout: mav0/{imu0, cam0, cam1, state_groundtruth_estimate0 | gt0}; cameras optional.
#include <filesystem>

#include "common/error.h"
#include "common/log.h"
#include "io/dataset_index.h"
#include "io/euroc_calibration.h"
#include "io/euroc_tables.h"

namespace vilslam {
namespace {

namespace fs = std::filesystem;

// IMU calibration; an empty or absent imu0/sensor.yaml leaves the defaults and is listed as a problem.
EurocImu imu_calibration(const fs::path& mav0, std::vector<std::string>& problems) {
  const fs::path yaml = mav0 / "imu0" / "sensor.yaml";
  EurocImu imu;
  if (fs::exists(yaml)) imu = read_euroc_imu_yaml(yaml.string());
  if (!imu.from_file) {
    const std::string msg = yaml.string() + ": no IMU calibration, using default noise and T_BS = identity";
    spdlog::warn("{}", msg);
    problems.push_back(msg);
  }
  return imu;
}

}  // namespace

DatasetIndex index_euroc(const std::string& root) {
  const fs::path mav0 = fs::path(root) / "mav0";
  if (!fs::is_directory(mav0)) throw InputError(root, "not an EuRoC ASL folder (no mav0/)");
  DatasetIndex index;
  index.summary.format = "euroc";
  index.summary.path = root;
  auto& problems = index.summary.problems;

  const fs::path imu_csv = mav0 / "imu0" / "data.csv";
  if (!fs::exists(imu_csv)) throw InputError(imu_csv.string(), "missing (an EuRoC folder needs imu0)");
  const EurocImu imu = imu_calibration(mav0, problems);
  RigCalibration& calib = index.calibration;
  calib.imu = imu.noise;
  index.imu = read_imu_csv(imu_csv.string());

  const bool cam0 = fs::is_directory(mav0 / "cam0");
  const bool cam1 = fs::is_directory(mav0 / "cam1");
  if (cam0 != cam1) throw InputError(mav0.string(), "has only one of cam0/ and cam1/ (stereo needs both)");
  if (cam0) {
    index.has_cameras = true;
    read_euroc_cameras(mav0.string(), imu.T_B_I, calib);
    validate_calibration(calib, mav0.string());
    const auto left_rows = read_camera_csv((mav0 / "cam0").string(), false, problems);
    const auto right_rows = read_camera_csv((mav0 / "cam1").string(), false, problems);
    index.stereo = pair_stereo(left_rows, right_rows, problems);
  }
  index.groundtruth = read_euroc_groundtruth(mav0.string(), imu.T_B_I);
  return index;
}

}  // namespace vilslam
