#pragma once
// Everything the simulator can be told, with defaults modelled on the paper's platform (stereo
// 752x480 grey at 20 Hz with a 0.3 m baseline, IMU at 200 Hz, a VLP-16 above the cameras).
// Loadable from YAML (config/sim_default.yaml lists every key); missing keys keep their defaults.
#include <string>

#include "common/calibration.h"
#include "sim/calibration_errors.h"
#include "sim/camera_render.h"
#include "sim/faults.h"
#include "sim/imu_sim.h"
#include "sim/lidar_sim.h"
#include "sim/trajectory.h"
#include "sim/world.h"

namespace vilslam::sim {

CameraIntrinsics default_camera();
// The simulator's camera: 2 grey levels of noise, no motion blur (5 ms exposure when blurred), vignetting 0.5.
RenderOptions default_render();

struct SimConfig {
  // Rig. Cameras look forward: the optical axis z_C0 is the body's forward axis x_I, x_C0 = -y_I
  // (right), y_C0 = -z_I (down). C1 sits baseline_m along x_C0 (to the right of C0).
  CameraIntrinsics camera = default_camera();  // both cameras (radtan when distortion_coeffs has 4 values)
  double stereo_baseline_m = 0.3;
  Vec3 p_I_C0_m = Vec3(0.10, 0.15, 0.0);       // left camera centre in the IMU frame
  Vec3 p_I_L_m = Vec3(0.05, 0.0, 0.20);        // LiDAR above the cameras, axes aligned with I
  LidarSimConfig lidar = lidar_sensor("vlp16");
  ImuSimConfig imu;
  RenderOptions render = default_render();     // noise_seed is set per frame
  double exposure_variation = 0.15;            // gain = 1 + variation * sin(2 pi t / period)
  double exposure_period_s = 9.0;

  // Motion: walking indoors, faster outdoors.
  RouteMotionConfig motion;                    // indoor speed, ramps, rests, sway
  double outdoor_speed_m_s = 4.0;
  double outdoor_ramp_s = 4.0;
  double outdoor_control_spacing_m = 6.0;
  PoseSplineConfig pose_spline;                // --trajectory files
  TimeNs start_time_ns = 1'000'000'000;        // timestamp of the first sample

  FaultConfig faults;
  // Sensor realism (docs/simulator.md): the IMU's errors (imu.errors), the LiDAR's return model, the render's
  // vignetting and blur and the calibration errors below apply while this is on, the default (`sensor_realism: false` or `--ideal-sensors`
  // turn it off).
  bool sensor_realism = true;
  CalibrationErrors calibration_errors;        // what the written calibration does not say
  double preview_duration_s = 1.5;
  double model_spacing_m = 0.05;               // reference model point spacing
  int parallel_batch = 16;                     // frames rendered in parallel before being written in order
};

// The config with ideal sensors (what the simulator renders when sensor_realism is off): no calibration
// errors, the IMU's data sheet (no axis errors, the noise as written), no missed LiDAR echoes, oblique-footprint spread or mixed pixels, no vignetting. Range and pixel
// noise, motion blur, exposure changes and faults stay as configured.
SimConfig ideal_sensors(SimConfig config);

// Throws InputError naming the file for missing files, YAML errors, unknown keys and bad values.
SimConfig load_sim_config(const std::string& path);

// The route motion of a scenario: walking indoors, the outdoor speed, ramp and spacing outdoors.
RouteMotionConfig route_motion_config(const SimConfig& config, Scenario scenario);

// The dataset's calibration: intrinsics, extrinsics and IMU noise (faults are not recorded).
RigCalibration rig_calibration(const SimConfig& config);

}  // namespace vilslam::sim
