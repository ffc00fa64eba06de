// The true sensor mounts: off the written calibration by exactly the configured angles and distances,
// about axes drawn from the seed, with the stereo baseline's length and direction kept and cam1 turned on cam0;
// the true lenses within the configured pixels of the written ones.
#include <gtest/gtest.h>

#include <cmath>

#include "sim/calibration_errors.h"
#include "sim/sim_config.h"

namespace vilslam::sim {
namespace {

double angle_deg(const SE3& a, const SE3& b) {
  return so3::log(a.rotation().transpose() * b.rotation()).norm() * 180.0 / M_PI;
}

TEST(CalibrationErrors, TrueMountsAreOffByTheConfiguredAmounts) {
  const RigCalibration nominal = rig_calibration(SimConfig{});
  CalibrationErrors e;
  e.camera_rotation_deg = 0.5;
  e.camera_translation_m = 0.01;
  e.lidar_rotation_deg = 0.8;
  e.lidar_translation_m = 0.02;
  const SensorMounts m = true_mounts(nominal, e, 42);
  EXPECT_NEAR(angle_deg(nominal.T_I_C0, m.T_I_C0), 0.5, 1e-9);
  EXPECT_NEAR((nominal.T_I_C0.translation() - m.T_I_C0.translation()).norm(), 0.01, 1e-12);
  EXPECT_NEAR(angle_deg(nominal.T_I_L, m.T_I_L), 0.8, 1e-9);
  EXPECT_NEAR((nominal.T_I_L.translation() - m.T_I_L.translation()).norm(), 0.02, 1e-12);
  // The pair moves as one body, and cam1 sits turned on cam0 by the stereo error about its own centre.
  const SE3 nominal_C0_C1 = nominal.T_I_C0.inverse() * nominal.T_I_C1, true_C0_C1 = m.T_I_C0.inverse() * m.T_I_C1;
  EXPECT_LT((nominal_C0_C1.translation() - true_C0_C1.translation()).norm(), 1e-12);
  EXPECT_NEAR(angle_deg(nominal_C0_C1, true_C0_C1), e.stereo_rotation_deg, 1e-9);
  // The lenses: each of fx, fy, cx, cy within +-0.5 px of the written ones, and not all equal to them.
  double moved_px = 0;
  for (const auto& [n, t] : {std::pair{nominal.cam0, m.cam0}, {nominal.cam1, m.cam1}}) {
    for (const double d : {t.fx - n.fx, t.fy - n.fy, t.cx - n.cx, t.cy - n.cy}) {
      EXPECT_LE(std::abs(d), e.intrinsics_px);
      moved_px += std::abs(d);
    }
    EXPECT_EQ(t.width_px, n.width_px);
  }
  EXPECT_GT(moved_px, 0.5);
  EXPECT_EQ(m.camera_offset_ns, s_to_ns(e.camera_time_offset_s));
  EXPECT_EQ(m.lidar_offset_ns, s_to_ns(e.lidar_time_offset_s));
  // Another seed, another direction; the same seed, the same mounts.
  const SensorMounts other = true_mounts(nominal, e, 43), again = true_mounts(nominal, e, 42);
  EXPECT_GT(angle_deg(m.T_I_C0, other.T_I_C0), 0.05);
  EXPECT_EQ(again.T_I_L.translation(), m.T_I_L.translation());
}

TEST(CalibrationErrors, NoErrorsKeepTheWrittenMounts) {
  const RigCalibration nominal = rig_calibration(SimConfig{});
  const SensorMounts m = true_mounts(nominal, no_calibration_errors(), 42);
  // Bit for bit: an ideal dataset is the one simulated before calibration errors existed.
  for (const auto& [a, b] : {std::pair{nominal.T_I_C0, m.T_I_C0}, {nominal.T_I_C1, m.T_I_C1}, {nominal.T_I_L, m.T_I_L}}) {
    EXPECT_EQ(a.quat().coeffs(), b.quat().coeffs());
    EXPECT_EQ(a.translation(), b.translation());
  }
  EXPECT_EQ(m.cam0.fx, nominal.cam0.fx);
  EXPECT_EQ(m.cam1.cy, nominal.cam1.cy);
  EXPECT_EQ(m.camera_offset_ns, 0);
  const SimConfig ideal = ideal_sensors(SimConfig{});
  EXPECT_EQ(ideal.calibration_errors.lidar_rotation_deg, 0);
  EXPECT_EQ(ideal.render.vignetting, 0);
  EXPECT_EQ(ideal.lidar.returns.mixed_pixel_probability, 0);
}

}  // namespace
}  // namespace vilslam::sim
