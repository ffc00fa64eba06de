#pragma once
// Calibration of a real IMU stream against a recorded ground truth, so that a simulated flight with the
// real IMU (`simulate --trajectory --imu`) renders images from the pose the IMU actually had.
//
// A motion-capture ground truth (EuRoC's Vicon) gives the pose of a body frame B in a world frame V.
// Neither is exactly the IMU's: B's axes are a hand-eye estimate of the IMU's, and V is levelled only
// approximately. For EuRoC V1_01 the raw mismatch is about 2.7 deg between the measured specific force
// at rest and V's vertical, which no gauge alignment of an estimate removes.
//
// The alignment only shapes the motion the images are rendered from; nothing derived from it (nor from the
// ground truth at all) is written into the calibration the estimator reads (sim/imu_stream_noise.h).
#include <memory>
#include <vector>

#include "common/lie.h"
#include "common/types.h"
#include "sim/trajectory.h"

namespace vilslam::sim {

struct ImuAlignment {
  Mat3 R_B_I = Mat3::Identity();          // IMU axes in the ground truth's body frame
  bool rotation_estimated = false;        // false: the motion turned about fewer than two axes, R_B_I = I
  Vec3 gyro_bias_rad_s = Vec3::Zero();    // constant part of the gyro bias
  Vec3 gravity_V_m_s2 = Vec3(0, 0, -9.81);  // gravity in the ground truth's world frame
  Vec3 accel_bias_m_s2 = Vec3::Zero();    // constant part of the accelerometer bias
  // RMS residuals (per axis) of the measurement models below, with the identity calibration
  // (R_B_I = I, zero biases, gravity along -z of V) and with the estimated one.
  double gyro_rms_identity_rad_s = 0, gyro_rms_rad_s = 0;
  double accel_rms_identity_m_s2 = 0, accel_rms_m_s2 = 0;
};

// Least squares over all samples of
//   gyro  = R_B_I^T omega_B(t) + b_g                       (Procrustes for R_B_I, alternated with b_g)
//   accel = R_B_I^T R_V_B(t)^T (a_V(t) - g_V) + b_a         (|g_V| = 9.81, alternating g_V and b_a)
// with omega_B, R_V_B, a_V from the recorded motion. R_B_I stays the identity when the rates span fewer
// than two axes. Throws std::invalid_argument for fewer than 10 samples.
ImuAlignment align_imu_to_motion(const BodyMotion& motion, const std::vector<ImuSample>& samples);

// The recorded motion re-expressed as the IMU's: T_W_I(t) = T_W_V T_V_B(t) T_B_I, with W the
// gravity-aligned frame (the smallest rotation of V that takes g_V to -z, about the motion's first
// position so that the flight stays where it was recorded) and T_B_I = (R_B_I, 0).
class ImuAlignedMotion : public BodyMotion {
 public:
  ImuAlignedMotion(std::unique_ptr<BodyMotion> recorded, const ImuAlignment& alignment);
  TimeNs start_ns() const override { return recorded_->start_ns(); }
  TimeNs end_ns() const override { return recorded_->end_ns(); }
  MotionState state(TimeNs t_ns) const override;
  const SE3& T_W_V() const { return T_W_V_; }

 private:
  std::unique_ptr<BodyMotion> recorded_;
  SE3 T_W_V_;
  Mat3 R_B_I_;
};

}  // namespace vilslam::sim
