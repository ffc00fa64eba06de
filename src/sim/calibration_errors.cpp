#include "sim/calibration_errors.h"

#include <algorithm>
#include <cmath>

#include "sim/rng.h"

namespace vilslam::sim {
namespace {

constexpr double kDegToRad = 3.14159265358979323846 / 180.0;

Vec3 unit_direction(Rng& rng) {
  // Uniform on the sphere: z uniform in [-1, 1], azimuth uniform.
  const double z = rng.uniform(-1.0, 1.0), phi = rng.uniform(0.0, 2.0 * M_PI);
  const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
  return Vec3(r * std::cos(phi), r * std::sin(phi), z);
}

// The sensor's true pose in I: the nominal one turned about its own centre and moved (both in I). The
// draws are made either way, so one sensor's error does not depend on whether the other has one; without
// an error the nominal pose is kept bit for bit.
SE3 perturbed(const SE3& T_I_S, double rotation_deg, double translation_m, Rng& rng) {
  const Vec3 axis = unit_direction(rng), direction = unit_direction(rng);
  if (rotation_deg == 0 && translation_m == 0) return T_I_S;
  return SE3(so3::exp(rotation_deg * kDegToRad * axis) * T_I_S.rotation(), T_I_S.translation() + translation_m * direction);
}

// Each of fx, fy, cx, cy off by a draw uniform in +-px (drawn either way).
CameraIntrinsics perturbed(const CameraIntrinsics& nominal, double px, Rng& rng) {
  CameraIntrinsics c = nominal;
  for (double* v : {&c.fx, &c.fy, &c.cx, &c.cy}) {
    const double d = rng.uniform(-px, px);
    if (px > 0) *v += d;
  }
  return c;
}

}  // namespace

CalibrationErrors no_calibration_errors() {
  return CalibrationErrors{0, 0, 0, 0, 0, 0, 0, 0};
}

SensorMounts true_mounts(const RigCalibration& nominal, const CalibrationErrors& errors, std::uint64_t seed) {
  Rng rng(seed);
  SensorMounts m;
  // The stereo pair moves as one body: its baseline is calibrated far better than its mount on the IMU.
  const SE3 T_C0_C1 = nominal.T_I_C0.inverse() * nominal.T_I_C1;
  m.T_I_C0 = perturbed(nominal.T_I_C0, errors.camera_rotation_deg, errors.camera_translation_m, rng);
  m.T_I_C1 = m.T_I_C0 * T_C0_C1;
  if (errors.camera_rotation_deg == 0 && errors.camera_translation_m == 0) m.T_I_C1 = nominal.T_I_C1;
  m.T_I_L = perturbed(nominal.T_I_L, errors.lidar_rotation_deg, errors.lidar_translation_m, rng);
  const Vec3 stereo_axis = unit_direction(rng);
  if (errors.stereo_rotation_deg != 0) {
    const SE3 T_C1_C1true(so3::exp(errors.stereo_rotation_deg * kDegToRad * stereo_axis), Vec3::Zero());
    m.T_I_C1 = m.T_I_C1 * T_C1_C1true;
  }
  m.cam0 = perturbed(nominal.cam0, errors.intrinsics_px, rng);
  m.cam1 = perturbed(nominal.cam1, errors.intrinsics_px, rng);
  m.camera_offset_ns = s_to_ns(errors.camera_time_offset_s);
  m.lidar_offset_ns = s_to_ns(errors.lidar_time_offset_s);
  return m;
}

}  // namespace vilslam::sim
