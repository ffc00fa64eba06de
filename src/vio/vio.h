#pragma once
// The stereo VIO: IMU samples and the visual frontend's stereo matches in, camera-rate optimized states
// and IMU-rate propagated poses out (paper Sec. "Stereo visual inertial odometry").
#include <deque>
#include <functional>
#include <optional>
#include <vector>

#include "common/calibration.h"
#include "common/types.h"
#include "frontend/stereo_match.h"
#include "vio/initializer.h"
#include "vio/loss_check.h"
#include "vio/propagator.h"
#include "vio/smoother.h"

namespace vilslam {

struct VioConfig {
  SmootherConfig smoother;
  InitializerConfig initializer;
  ImuGapModel imu_gap;  // samples missing: the IMU factor across them is weakened (vio/preintegration.h)
  VioLossConfig loss;   // when the VIO declares itself lost and starts again (vio/loss_check.h)
  // Standard deviations of the first state's prior: rotation (rad), position (m), velocity (m/s),
  // gyro bias (rad/s), accel bias (m/s^2). Yaw and position are a gauge choice; a moving start gets
  // wider rotation and velocity priors (the averaged specific force then includes the acceleration).
  double prior_rotation_sigma_rad = 0.02;
  double moving_rotation_sigma_rad = 0.1;
  double prior_position_sigma_m = 1e-3;
  double prior_velocity_sigma_m_s = 0.05;
  double moving_velocity_sigma_m_s = 1.0;
  double prior_gyro_bias_sigma_rad_s = 0.01;
  double prior_accel_bias_sigma_m_s2 = 0.2;
};

// Optimized state at a stereo frame.
struct VioStateOutput {
  NavState state;
  Mat15 covariance;  // tangent ordering of window_state.h
  int landmarks = 0;        // with a vision factor in the window's last solve
  int frame_matches = 0;    // the frontend's stereo matches in this state's frame
  double imu_gap_s = 0;     // of the interval from the previous state, seconds without IMU samples (ImuGapModel)
  bool restarted = false;   // the first state of a window started again after a loss (VioLossEvent)
};

// The VIO lost track at a frame (vio/loss_check.h): that frame's state was not published, the window was dropped,
// and no state or IMU-rate pose follows until it has initialized again by visual-inertial alignment, continuing in
// yaw and position from the last published state.
struct VioLossEvent {
  TimeNs t_ns = 0;
  VioLoss reason = VioLoss::kNone;
  int frame_matches = 0;
  int landmarks = 0;
};

// Propagated state at an IMU sample. T_W_I jumps where a new optimized state re-anchors the propagation;
// T_O_I is the same motion without those jumps, in a frame O that drifts from W: over a LiDAR sweep its
// relative poses are the IMU's motion alone (what dewarping needs), never a smoother correction.
struct VioImuOutput {
  TimeNs t_ns = 0;
  SE3 T_W_I;
  Vec3 v_W_m_s = Vec3::Zero();
  SE3 T_O_I;
  // The tilt standard deviation of the state it was propagated from (tilt_sigma_rad, vio/window_state.h): about
  // what the VIO's own gravity direction is worth, large after a start while tilt and accel bias are entangled.
  double tilt_sigma_rad = 0.0;
};

class Vio {
 public:
  // Throws InputError when cam0 has no positive focal length.
  explicit Vio(const RigCalibration& calib, const VioConfig& config = {});

  // Samples must arrive in strictly increasing time; feed every sample up to a frame's time before it.
  // Throws InputError for a sample out of order or not finite.
  void add_imu(const ImuSample& sample);
  // Throws InputError for a frame out of order. A frame before any IMU sample is skipped. With
  // config.initializer.moving_start the first frames wait for the visual-inertial alignment; once it succeeds
  // they are all handed to the smoother (their states published then), while it fails the oldest is dropped.
  void add_frame(const FrontendOutput& frame);

  void on_state(std::function<void(const VioStateOutput&)> callback) { on_state_ = std::move(callback); }
  void on_imu_pose(std::function<void(const VioImuOutput&)> callback) { on_imu_ = std::move(callback); }
  void on_lost(std::function<void(const VioLossEvent&)> callback) { on_lost_ = std::move(callback); }

  bool initialized() const { return smoother_.initialized(); }
  const std::optional<VioStateOutput>& latest_state() const { return latest_state_; }
  const std::optional<VioImuOutput>& latest_imu_pose() const { return latest_imu_; }
  const Smoother& smoother() const { return smoother_; }

 private:
  void publish_state(const FrontendOutput& frame, double imu_gap_s);
  // The first frame, or the first after a loss: a static start, or the alignment window when moving.
  void start(const FrontendOutput& frame);
  // moving_start (or a restart while moving): collects the alignment window, initializes from it once it aligns.
  void initialize_moving(const FrontendOutput& frame);
  // Starts the smoother's window at x0; after a loss, continues from the last published state's yaw and position.
  void begin_window(const NavState& x0, const Vec15& prior_sigma, const FrontendOutput& frame);
  void declare_lost(const FrontendOutput& frame, VioLoss reason);
  // The IMU-rate poses of samples after the newest state up to t_ns (an aligned window's, once it aligned).
  void publish_imu_poses(const std::vector<ImuSample>& samples, TimeNs t_ns);

  VioConfig config_;
  RigCalibration calib_;
  Smoother smoother_;
  Propagator propagator_;
  std::vector<ImuSample> imu_;  // samples from just before the newest state on
  std::deque<FrontendOutput> alignment_frames_;  // moving_start: the window not yet aligned
  VioLossCheck loss_check_;
  bool restarting_ = false;  // lost: the next window continues from the last published state
  bool restarted_ = false;   // the next published state is a restarted window's first
  std::optional<VioStateOutput> latest_state_;
  std::optional<VioImuOutput> latest_imu_;
  SE3 T_O_W_;  // the jump-free frame O of VioImuOutput::T_O_I
  std::function<void(const VioStateOutput&)> on_state_;
  std::function<void(const VioImuOutput&)> on_imu_;
  std::function<void(const VioLossEvent&)> on_lost_;
};

}  // namespace vilslam
