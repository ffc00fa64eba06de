// `vilslam calibrate-lidar DATASET --lidar-poses LIDAR.tum --out RIG.yaml`: the LiDAR mount's rotation from how
// the rig turned, the dataset's gyroscope against the LiDAR's odometry (calib/mount_rotation.h), written as the
// dataset's calibration with T_I_L's rotation replaced, for `vilslam run --calib RIG.yaml` (docs/calibration.md).
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>

#include "calib/mount_rotation.h"
#include "common/error.h"
#include "common/json_writer.h"
#include "io/calibration_io.h"
#include "io/dataset_index.h"
#include "io/trajectory_io.h"
#include "vilslam/command.h"
#include "vilslam/dataset_options.h"

namespace {

using namespace vilslam;

constexpr double kDeg = 180.0 / M_PI;

struct Options {
  std::string dataset, lidar_poses, out, json_path;
  calib::MountRotationConfig config;
  double min_rotation_deg = 20.0;
  int min_windows = 10;
};

Trajectory read_sorted(const std::string& path) {
  const Trajectory poses = read_trajectory(path, TrajectoryFormat::kTum);
  if (poses.size() < 2) throw InputError(path, "fewer than 2 poses");
  for (std::size_t i = 1; i < poses.size(); ++i) {
    if (poses[i].t_ns <= poses[i - 1].t_ns) throw InputError(path, "timestamps not increasing", static_cast<long>(i + 1));
  }
  return poses;
}

vilslam::cli::Command reg("calibrate-lidar", "The LiDAR mount's rotation from the rig's turns (hand-eye)", [](CLI::App& app) {
  auto o = std::make_shared<Options>();
  auto dataset_args = cli::add_dataset_options(app);
  app.add_option("dataset", o->dataset, "Dataset whose calibration is refined (folder or ROS1 .bag)")->required();
  app.add_option("--lidar-poses", o->lidar_poses,
                 "T_W_L of the LiDAR's odometry on it (TUM; `vilslam run` lidar.tum, docs/calibration.md)")
      ->required();
  app.add_option("--out", o->out, "Rig YAML to write: the dataset's calibration with the refined T_I_L")->required();
  app.add_option("--window", o->config.window_s, "Seconds each relative rotation spans")
      ->check(CLI::Range(0.2, 60.0))
      ->capture_default_str();
  app.add_option("--min-rotation-deg", o->min_rotation_deg, "A window turning this much counts as a turn (--min-windows)")
      ->check(CLI::Range(1.0, 180.0))
      ->capture_default_str();
  app.add_option("--min-windows", o->min_windows, "Fewer windows that turn enough are an error")
      ->check(CLI::Range(1, 100000))
      ->capture_default_str();
  app.add_option("--json", o->json_path, "Also write the estimate as JSON to this file");
  return [o, dataset_args]() {
    const DatasetIndex index = index_dataset(o->dataset, cli::dataset_options(*dataset_args));
    const RigCalibration& nominal = index.calibration;
    if (!nominal.has_lidar) throw InputError(o->dataset, "the dataset's calibration has no LiDAR");
    if (index.imu.size() < 2) throw InputError(o->dataset, "fewer than 2 IMU samples");
    const Trajectory T_W_L = read_sorted(o->lidar_poses);
    o->config.stride_s = o->config.window_s / 2.0;
    o->config.min_rotation_rad = o->min_rotation_deg / kDeg;
    const Mat3 R_nominal = nominal.T_I_L.rotation();
    const calib::MountRotationEstimate e = calib::estimate_mount_rotation(index.imu, T_W_L, R_nominal, o->config);
    if (e.turning_windows < o->min_windows) {
      throw InputError(o->lidar_poses, "the route turns too little to calibrate: " + std::to_string(e.turning_windows) +
                                           " windows of " + std::to_string(o->config.window_s) + " s turn " +
                                           std::to_string(o->min_rotation_deg) + " deg or more (--min-windows " +
                                           std::to_string(o->min_windows) + ")");
    }
    const Vec3 sigma_deg = e.covariance_rad2.diagonal().cwiseSqrt() * kDeg;
    const Vec3 correction_deg = e.correction_rad * kDeg;
    std::printf("windows %d, of which %d turn >= %.1f deg in %.1f s; rms residual of those %.4f deg\n", e.windows,
                e.turning_windows, o->min_rotation_deg, o->config.window_s, e.rms_residual_rad * kDeg);
    std::printf("gyroscope bias (rad/s, I): %+.6f %+.6f %+.6f\n", e.gyro_bias_rad_s.x(), e.gyro_bias_rad_s.y(),
                e.gyro_bias_rad_s.z());
    std::printf("correction in L (deg): x %+.4f (sigma %.4f)  y %+.4f (sigma %.4f)  z %+.4f (sigma %.4f; 0: kept)\n",
                correction_deg.x(), sigma_deg.x(), correction_deg.y(), sigma_deg.y(), correction_deg.z(), sigma_deg.z());
    std::printf("directions estimated: %d of 3 (the others, known worse than %.2f deg, keep the nominal)\n",
                e.estimated_directions, o->config.max_sigma_rad * kDeg);
    if (e.estimated_directions == 2) {
      std::printf("kept at the nominal: the rotation about the axis (%.3f %.3f %.3f) in L, the turns' axis\n",
                  e.kept_direction.x(), e.kept_direction.y(), e.kept_direction.z());
    }
    RigCalibration refined = nominal;
    refined.T_I_L = SE3(e.R_I_L, nominal.T_I_L.translation());
    if (!o->json_path.empty()) {
      JsonWriter json;
      json.begin_object();
      json.key("windows").value(e.windows);
      json.key("turning_windows").value(e.turning_windows);
      json.key("estimated_directions").value(e.estimated_directions);
      json.key("rms_residual_deg").value(e.rms_residual_rad * kDeg);
      json.key("correction_deg").begin_array();
      for (int i = 0; i < 3; ++i) json.value(correction_deg[i]);
      json.end_array();
      json.key("sigma_deg").begin_array();
      for (int i = 0; i < 3; ++i) json.value(sigma_deg[i]);
      json.end_array();
      json.end_object();
      write_file_atomic(o->json_path, json.str());
    }
    write_rig_yaml(o->out, refined);
    std::printf("wrote %s\n", o->out.c_str());
    return 0;
  };
});

}  // namespace
