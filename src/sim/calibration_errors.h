#pragma once
// Calibration errors the estimator is not told (docs/simulator.md, "Sensor realism"): the sensors sit a
// little off the extrinsics written to the dataset's calibration, the cameras' intrinsics and the second
// camera's pose on the first are a little off theirs, and the sensors stamp their data with clock offsets.
// The written calibration stays the nominal one; the simulator renders and scans with the true ones.
#include <cstdint>

#include "common/calibration.h"
#include "common/time.h"

namespace vilslam::sim {

struct CalibrationErrors {
  // The stereo pair (as one rigid body) and the LiDAR are rotated by these angles about an axis, and moved
  // by these distances along a direction, both drawn from the seed; Kalibr-grade camera-IMU and hand-measured
  // LiDAR-IMU calibrations are off by about this much.
  double camera_rotation_deg = 0.5;
  double camera_translation_m = 0.01;
  double lidar_rotation_deg = 0.5;
  double lidar_translation_m = 0.01;
  double camera_time_offset_s = 0.003;  // stamp = true capture time + offset
  double lidar_time_offset_s = -0.002;
  // A stereo calibration's own errors (Kalibr's repeatability): cam1 turned on cam0 by this angle about a drawn
  // axis (about its own centre), and each camera's fx, fy, cx, cy off by a draw uniform in +-intrinsics_px.
  double stereo_rotation_deg = 0.1;
  double intrinsics_px = 0.5;
};

// No error: the true mounts are the written ones and the stamps are the capture times.
CalibrationErrors no_calibration_errors();

// Where the sensors really are, what their lenses really are and how their clocks are off.
struct SensorMounts {
  SE3 T_I_C0, T_I_C1, T_I_L;
  CameraIntrinsics cam0, cam1;
  TimeNs camera_offset_ns = 0;
  TimeNs lidar_offset_ns = 0;
};

// The true mounts and intrinsics for the nominal calibration: each error's axis or direction is uniform on the
// sphere, a pure function of seed (the stereo and intrinsics draws come after the others, which stay those of
// before they existed).
SensorMounts true_mounts(const RigCalibration& nominal, const CalibrationErrors& errors, std::uint64_t seed);

}  // namespace vilslam::sim
