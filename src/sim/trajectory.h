#pragma once
// Smooth rig trajectories with analytic derivatives: a closed route flown from rest to rest, or a
// spline fitted to a recorded ground truth. Query any instant for pose, velocity, acceleration and the
// body angular rate, from which the IMU is simulated exactly.
#include <memory>
#include <vector>

#include "common/lie.h"
#include "common/time.h"
#include "common/types.h"
#include "sim/spline.h"

namespace vilslam::sim {

struct MotionState {
  TimeNs t_ns = 0;
  SE3 T_W_I;
  Vec3 v_W = Vec3::Zero();       // m/s
  Vec3 a_W = Vec3::Zero();       // m/s^2 (kinematic, without gravity)
  Vec3 omega_I = Vec3::Zero();   // rad/s, body angular rate in I
};

class BodyMotion {
 public:
  virtual ~BodyMotion() = default;
  virtual TimeNs start_ns() const = 0;
  virtual TimeNs end_ns() const = 0;
  // Clamped to [start_ns, end_ns].
  virtual MotionState state(TimeNs t_ns) const = 0;
  SE3 pose(TimeNs t_ns) const { return state(t_ns).T_W_I; }
};

struct RouteMotionConfig {
  double cruise_speed_m_s = 1.2;
  double ramp_s = 2.0;             // time to reach cruise speed from rest (and to stop)
  double rest_start_s = 1.0;       // standing still before moving
  double rest_end_s = 1.0;         // standing still after stopping
  double control_spacing_m = 2.0;  // route legs are resampled at this spacing as B-spline controls
  double roll_amplitude_deg = 1.5; // sway, a periodic function of the distance travelled
  double pitch_amplitude_deg = 1.0;
  double sway_wavelength_m = 1.4;
  int laps = 1;                    // times round the closed route before stopping where it started
  TimeNs start_ns = 0;
};

// A closed route (first waypoint == last) as a periodic cubic B-spline, arc-length parametrized,
// flown config.laps times with a speed profile that is at rest at both ends (so the end pose equals the
// start pose).
// Yaw follows the horizontal direction of travel, pitch the slope; roll and pitch sway smoothly with
// the distance.
class RouteMotion : public BodyMotion {
 public:
  RouteMotion(const std::vector<Vec3>& route_W, const RouteMotionConfig& config);
  TimeNs start_ns() const override { return config_.start_ns; }
  TimeNs end_ns() const override;
  MotionState state(TimeNs t_ns) const override;
  double length_m() const { return total_length_m_; }  // of one lap
  double cruise_speed_m_s() const { return cruise_speed_m_s_; }
  // Cruise speed that makes the whole motion (config.laps laps of length_m) last duration_s (rests and ramps
  // included).
  static double cruise_speed_for_duration(double length_m, double duration_s, const RouteMotionConfig& config);

 private:
  double parameter_at_length(double s_m) const;  // spline parameter u at arc length s
  double length_at_parameter(double u) const;
  // Distance travelled and its first two time derivatives at tau seconds after the start.
  Eigen::Vector3d distance_profile(double tau_s) const;

  RouteMotionConfig config_;
  UniformBSpline curve_;
  std::vector<double> segment_start_length_m_;  // arc length at u = i
  double total_length_m_ = 0;   // one lap
  double travel_m_ = 0;         // all laps
  double cruise_speed_m_s_ = 0;
  double ramp_s_ = 0;
  double cruise_s_ = 0;
};

struct PoseSplineConfig {
  double knot_spacing_s = 0.05;  // least-squares B-spline over all poses: smooths tracker noise
  double smoothing = 1e-3;
};

// A recorded trajectory (e.g. EuRoC ground truth) as a C2 spline through its poses: position and the
// sign-continuous quaternion are fitted together, the quaternion renormalized on evaluation.
class PoseSplineMotion : public BodyMotion {
 public:
  // Throws std::invalid_argument when there are fewer than 2 poses or they span no time.
  explicit PoseSplineMotion(const Trajectory& poses, const PoseSplineConfig& config = {});
  TimeNs start_ns() const override { return start_ns_; }
  TimeNs end_ns() const override { return end_ns_; }
  MotionState state(TimeNs t_ns) const override;

 private:
  TimeNs start_ns_ = 0;
  TimeNs end_ns_ = 0;
  double knot_spacing_s_ = 0;
  UniformBSpline spline_;
};

}  // namespace vilslam::sim
