#include "vio/vio.h"

#include <algorithm>
#include <cmath>

#include "common/error.h"
#include "vio/visual_inertial_alignment.h"

namespace vilslam {
namespace {

constexpr const char* kSource = "vio input";

// cam0's focal length, which converts the pixel noise into normalized coordinates.
double checked_focal_px(const RigCalibration& calib) {
  if (!(calib.cam0.fx > 0) || !std::isfinite(calib.cam0.fx)) {
    throw InputError("calibration", "cam0 focal length must be positive for the VIO's pixel noise");
  }
  return calib.cam0.fx;
}

}  // namespace

Vio::Vio(const RigCalibration& calib, const VioConfig& config)
    : config_(config),
      calib_(calib),
      smoother_(config.smoother, {calib.T_I_C0, calib.T_I_C1}, calib.imu, checked_focal_px(calib)),
      propagator_(calib.imu, Vec3(0, 0, -config.smoother.gravity_m_s2)),
      loss_check_(config.loss, config.smoother.window_size) {}

void Vio::add_imu(const ImuSample& sample) {
  if (!sample.gyro_rad_s.allFinite() || !sample.accel_m_s2.allFinite()) {
    throw InputError(kSource, "IMU sample at t_ns " + std::to_string(sample.t_ns) + " is not finite");
  }
  if (!imu_.empty() && sample.t_ns <= imu_.back().t_ns) {
    throw InputError(kSource, "IMU sample at t_ns " + std::to_string(sample.t_ns) + " is not after the previous one");
  }
  imu_.push_back(sample);
  if (!initialized() || sample.t_ns <= smoother_.newest().t_ns) return;
  const NavState x = propagator_.add(sample);
  latest_imu_ = VioImuOutput{x.t_ns, x.T_W_I(), x.v_W_m_s, T_O_W_ * x.T_W_I(),
                             tilt_sigma_rad(smoother_.newest(), smoother_.newest_covariance())};
  if (on_imu_) on_imu_(*latest_imu_);
}

void Vio::add_frame(const FrontendOutput& frame) {
  if (initialized() && frame.t_ns <= smoother_.newest().t_ns) {
    throw InputError(kSource, "frame at t_ns " + std::to_string(frame.t_ns) + " is not after the previous one");
  }
  if (imu_.empty() || imu_.front().t_ns > frame.t_ns) return;
  if (!initialized()) {
    start(frame);
    return;
  }
  const TimeNs join_t_ns = std::max(propagator_.current().t_ns, frame.t_ns);  // old and new propagation joined in O
  const SE3 T_W_I_old = propagator_.state_at(join_t_ns).T_W_I();
  const NavState& x = smoother_.newest();
  Preintegration preint(x.bias_gyro_rad_s, x.bias_accel_m_s2, calib_.imu);
  const double imu_gap_s =
      integrate_samples(samples_for_frame(imu_, frame.t_ns, config_.imu_gap.max_step_s), x.t_ns, frame.t_ns, preint,
                        config_.imu_gap);
  smoother_.add_frame(preint, frame);
  const VioLoss loss = loss_check_.check(smoother_.newest(), smoother_.newest_covariance(),
                                         static_cast<int>(frame.matches.size()), smoother_.stats().landmarks,
                                         smoother_.stats().final_cost);
  if (loss != VioLoss::kNone) {
    declare_lost(frame, loss);
    return;
  }
  drop_samples_before(imu_, smoother_.newest().t_ns);
  propagator_.reset(smoother_.newest(), imu_);
  // O stays continuous: the new propagation at the join time maps to where the old one was.
  T_O_W_ = T_O_W_ * T_W_I_old * propagator_.state_at(join_t_ns).T_W_I().inverse();
  publish_state(frame, imu_gap_s);
}

void Vio::start(const FrontendOutput& frame) {
  // A moving start and a restart align (a rig at constant velocity looks static to the IMU alone).
  if (config_.initializer.moving_start || restarting_ || !alignment_frames_.empty()) {
    initialize_moving(frame);
    return;
  }
  const Initialization init = static_initialization(imu_, frame.t_ns, config_.initializer);
  Vec15 sigma;
  sigma << Vec3::Constant(init.is_static ? config_.prior_rotation_sigma_rad : config_.moving_rotation_sigma_rad),
      Vec3::Constant(config_.prior_position_sigma_m),
      Vec3::Constant(init.is_static ? config_.prior_velocity_sigma_m_s : config_.moving_velocity_sigma_m_s),
      Vec3::Constant(config_.prior_gyro_bias_sigma_rad_s), Vec3::Constant(config_.prior_accel_bias_sigma_m_s2);
  begin_window(init.state, sigma, frame);
  drop_samples_before(imu_, smoother_.newest().t_ns);
  propagator_.reset(smoother_.newest(), imu_);
  publish_state(frame, 0.0);
}

void Vio::initialize_moving(const FrontendOutput& frame) {
  if (!alignment_frames_.empty() && frame.t_ns <= alignment_frames_.back().t_ns) {
    throw InputError(kSource, "frame at t_ns " + std::to_string(frame.t_ns) + " is not after the previous one");
  }
  alignment_frames_.push_back(frame);
  if (alignment_frames_.size() < static_cast<std::size_t>(config_.initializer.alignment.frames)) return;
  const std::vector<FrontendOutput> window(alignment_frames_.begin(), alignment_frames_.end());
  const VisualInertialAlignment a = align_visual_inertial(window, imu_, calib_, calib_.cam0.fx,
                                                          config_.smoother.gravity_m_s2, config_.initializer.alignment);
  if (!a.state) {
    alignment_frames_.pop_front();
    drop_samples_before(imu_, alignment_frames_.front().t_ns);
    return;
  }
  Vec15 sigma;
  sigma << Vec3::Constant(config_.prior_rotation_sigma_rad), Vec3::Constant(config_.prior_position_sigma_m),
      Vec3::Constant(config_.moving_velocity_sigma_m_s), Vec3::Constant(config_.prior_gyro_bias_sigma_rad_s),
      Vec3::Constant(config_.prior_accel_bias_sigma_m_s2);
  alignment_frames_.clear();
  // The LiDAR side maps no sweep before the VIO's poses begin (and after a loss, maps without them): the poses
  // are published from the window's first frame on, as they would have been live.
  const std::vector<ImuSample> samples = imu_;
  begin_window(*a.state, sigma, window.front());
  propagator_.reset(smoother_.newest(), imu_);
  publish_state(window.front(), 0.0);
  for (std::size_t k = 1; k < window.size(); ++k) {
    // Lost again on one of these frames: no window to publish from, and the rest start the next alignment.
    if (initialized()) publish_imu_poses(samples, window[k].t_ns);
    add_frame(window[k]);
  }
}

void Vio::publish_imu_poses(const std::vector<ImuSample>& samples, TimeNs t_ns) {
  // As they would have been published live: propagated from the newest state, sample by sample.
  const NavState& x = smoother_.newest();
  const auto first_after = first_sample_after(samples, x.t_ns);
  Propagator propagator(calib_.imu, smoother_.gravity_W());
  propagator.reset(x, std::vector<ImuSample>(samples.begin(), first_after));
  const double x_tilt_sigma_rad = tilt_sigma_rad(x, smoother_.newest_covariance());  // one state for all samples
  for (auto it = first_after; it != samples.end() && it->t_ns <= t_ns; ++it) {
    const NavState y = propagator.add(*it);
    latest_imu_ = VioImuOutput{y.t_ns, y.T_W_I(), y.v_W_m_s, T_O_W_ * y.T_W_I(), x_tilt_sigma_rad};
    if (on_imu_) on_imu_(*latest_imu_);
  }
}

void Vio::begin_window(const NavState& x0, const Vec15& prior_sigma, const FrontendOutput& frame) {
  NavState x = x0;
  if (restarting_ && latest_state_) {
    // Yaw and position are a gauge the restarted window cannot observe: it continues from the last published
    // state, moved on at the aligned velocity (the lost window's own is not trusted), so the output does not jump
    // (the error that state had stays).
    const NavState& last = latest_state_->state;
    const Mat3 R_shift = so3::rot_z(so3::yaw_rad(last.R_W_I) - so3::yaw_rad(x0.R_W_I));
    x.R_W_I = R_shift * x0.R_W_I;
    x.v_W_m_s = R_shift * x0.v_W_m_s;
    x.p_W_I = last.p_W_I + x.v_W_m_s * ns_to_s(x0.t_ns - last.t_ns);
  }
  smoother_.initialize(x, prior_sigma, frame);
  if (restarting_ && latest_imu_) T_O_W_ = latest_imu_->T_O_I * x.T_W_I().inverse();  // O continues where it was
  restarted_ = restarting_;
  restarting_ = false;
  loss_check_.reset();
}

void Vio::declare_lost(const FrontendOutput& frame, VioLoss reason) {
  const VioLossEvent event{frame.t_ns, reason, static_cast<int>(frame.matches.size()), smoother_.stats().landmarks};
  smoother_.reset();
  loss_check_.reset();
  restarting_ = true;
  drop_samples_before(imu_, frame.t_ns);
  if (on_lost_) on_lost_(event);
}

void Vio::publish_state(const FrontendOutput& frame, double imu_gap_s) {
  latest_state_ = VioStateOutput{smoother_.newest(), smoother_.newest_covariance(), smoother_.stats().landmarks,
                                 static_cast<int>(frame.matches.size()), imu_gap_s, restarted_};
  restarted_ = false;
  if (on_state_) on_state_(*latest_state_);
}

}  // namespace vilslam
