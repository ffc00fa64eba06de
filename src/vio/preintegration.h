#pragma once
// IMU preintegration on the manifold (Forster et al., "On-Manifold Preintegration for Real-Time
// Visual-Inertial Odometry", T-RO 2017). Deltas, first-order bias Jacobians and the 9x9 covariance of
// [dphi, dv, dp] are propagated sample by sample with Euler steps (eq. (38) / Appendix A, B).
#include <Eigen/Core>
#include <vector>

#include "common/calibration.h"
#include "common/types.h"

namespace vilslam {

using Mat9 = Eigen::Matrix<double, 9, 9>;

// Samples missing from the stream (an IMU gap, docs/vio.md "IMU gaps"): across a step longer than
// max_step_s the interpolated measurement is a guess, off by the rig's unmeasured motion. That error is
// held over the step, not white: its 1-sigma rate and acceleration enter the step's noise undivided by dt,
// so the factor's covariance grows as (sigma dt)^2 and the smoother leans on vision across the gap.
struct ImuGapModel {
  double max_step_s = 0.05;           // longer sample intervals are gaps (nominal IMU periods: 2.5-10 ms)
  double rate_sigma_rad_s = 1.0;      // angular rate the rig may have had that the held sample misses
  double accel_sigma_m_s2 = 3.0;      // likewise, acceleration
};

class Preintegration {
 public:
  // Preintegrates with the bias estimate (bias_gyro, bias_accel) held fixed (Forster's b_bar_i).
  Preintegration(const Vec3& bias_gyro_rad_s, const Vec3& bias_accel_m_s2, const ImuNoise& noise);

  // One Euler step of length dt_s with raw measurements held constant over the step. held: the 1-sigma
  // error of the held measurements themselves (ImuGapModel; zero when the samples are there).
  void integrate(const Vec3& gyro_rad_s, const Vec3& accel_m_s2, double dt_s, double held_rate_sigma_rad_s = 0,
                 double held_accel_sigma_m_s2 = 0);

  double dt_s() const { return dt_s_; }
  const Vec3& bias_gyro_lin() const { return bias_gyro_; }
  const Vec3& bias_accel_lin() const { return bias_accel_; }
  const Mat3& delta_R() const { return delta_R_; }
  const Vec3& delta_v() const { return delta_v_; }
  const Vec3& delta_p() const { return delta_p_; }
  const Mat3& dR_dbg() const { return dR_dbg_; }
  const Mat3& dv_dbg() const { return dv_dbg_; }
  const Mat3& dv_dba() const { return dv_dba_; }
  const Mat3& dp_dbg() const { return dp_dbg_; }
  const Mat3& dp_dba() const { return dp_dba_; }
  // Covariance of the preintegrated noise [dphi; dv; dp] (eq. (62)).
  const Mat9& covariance() const { return covariance_; }

  // Deltas corrected to the biases (bg, ba) to first order (eq. (44)).
  Mat3 corrected_delta_R(const Vec3& bias_gyro_rad_s) const;
  Vec3 corrected_delta_v(const Vec3& bias_gyro_rad_s, const Vec3& bias_accel_m_s2) const;
  Vec3 corrected_delta_p(const Vec3& bias_gyro_rad_s, const Vec3& bias_accel_m_s2) const;

 private:
  Vec3 bias_gyro_, bias_accel_;
  ImuNoise noise_;
  double dt_s_ = 0;
  Mat3 delta_R_ = Mat3::Identity();
  Vec3 delta_v_ = Vec3::Zero(), delta_p_ = Vec3::Zero();
  Mat3 dR_dbg_ = Mat3::Zero(), dv_dbg_ = Mat3::Zero(), dv_dba_ = Mat3::Zero();
  Mat3 dp_dbg_ = Mat3::Zero(), dp_dba_ = Mat3::Zero();
  Mat9 covariance_ = Mat9::Zero();
};

// Integrates the samples over [t0_ns, t1_ns]. The signal is taken as piecewise linear between samples;
// each Euler step spans the overlap of [t0, t1] with one sample interval and uses the interpolated
// measurement at the step's midpoint. Outside the samples' span the nearest sample is held. A step inside a
// sample interval longer than gap.max_step_s carries gap's held-measurement noise. Returns the seconds of
// [t0, t1] that lay in such gaps.
// Throws std::invalid_argument when samples is empty or t1_ns < t0_ns.
double integrate_samples(const std::vector<ImuSample>& samples, TimeNs t0_ns, TimeNs t1_ns, Preintegration& preint,
                       const ImuGapModel& gap = {});

// The first of the time-sorted samples after t_ns (end() when none is).
std::vector<ImuSample>::const_iterator first_sample_after(const std::vector<ImuSample>& samples, TimeNs t_ns);
// The samples a frame at t_ns is integrated with: those up to t_ns, and the next one only when it ends an
// IMU gap (an interval above max_step_s, interpolated across as ImuGapModel says). Whether the next sample has
// arrived when the frame is integrated then does not matter: offline it has not (a frame is released before
// the sample that passes it), live it may have (a late frame), and both give the same state.
std::vector<ImuSample> samples_for_frame(const std::vector<ImuSample>& samples, TimeNs t_ns, double max_step_s);
// Drops the samples before the last one at or before t_ns: what integrating from t_ns on still needs.
void drop_samples_before(std::vector<ImuSample>& samples, TimeNs t_ns);

}  // namespace vilslam
