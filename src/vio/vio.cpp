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
      propagator_(calib.imu, Vec3(0, 0, -config.smoother.gravity_m_s2)) {}

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
  latest_imu_ = VioImuOutput{x.t_ns, x.T_W_I(), x.v_W_m_s, T_O_W_ * x.T_W_I()};
  if (on_imu_) on_imu_(*latest_imu_);
}

void Vio::add_frame(const FrontendOutput& frame) {
  if (initialized() && frame.t_ns <= smoother_.newest().t_ns) {
    throw InputError(kSource, "frame at t_ns " + std::to_string(frame.t_ns) + " is not after the previous one");
  }
  if (imu_.empty() || imu_.front().t_ns > frame.t_ns) return;
  if (!initialized() && config_.initializer.moving_start) {
    initialize_moving(frame);
    return;
  }
  std::optional<TimeNs> join_t_ns;  // where the old and the new propagation are joined in O
  std::optional<SE3> T_W_I_old;
  double imu_gap_s = 0;
  if (!initialized()) {
    const Initialization init = static_initialization(imu_, frame.t_ns, config_.initializer);
    Vec15 sigma;
    sigma << Vec3::Constant(init.is_static ? config_.prior_rotation_sigma_rad : config_.moving_rotation_sigma_rad), Vec3::Constant(config_.prior_position_sigma_m),
        Vec3::Constant(init.is_static ? config_.prior_velocity_sigma_m_s : config_.moving_velocity_sigma_m_s),
        Vec3::Constant(config_.prior_gyro_bias_sigma_rad_s), Vec3::Constant(config_.prior_accel_bias_sigma_m_s2);
    smoother_.initialize(init.state, sigma, frame);
  } else {
    join_t_ns = std::max(propagator_.current().t_ns, frame.t_ns);
    T_W_I_old = propagator_.state_at(*join_t_ns).T_W_I();
    const NavState& x = smoother_.newest();
    Preintegration preint(x.bias_gyro_rad_s, x.bias_accel_m_s2, calib_.imu);
    imu_gap_s = integrate_samples(imu_, x.t_ns, frame.t_ns, preint, config_.imu_gap);
    smoother_.add_frame(preint, frame);
  }
  // Keep the samples from the last one at or before the newest state on.
  const TimeNs t_ns = smoother_.newest().t_ns;
  const auto first_after = std::upper_bound(imu_.begin(), imu_.end(), t_ns,
                                            [](TimeNs t, const ImuSample& s) { return t < s.t_ns; });
  imu_.erase(imu_.begin(), first_after == imu_.begin() ? first_after : first_after - 1);
  propagator_.reset(smoother_.newest(), imu_);
  if (T_W_I_old) {
    // O stays continuous: the new propagation at the join time maps to where the old one was.
    T_O_W_ = T_O_W_ * *T_W_I_old * propagator_.state_at(*join_t_ns).T_W_I().inverse();
  }
  publish_state(frame, imu_gap_s);
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
    // Keep the samples from the last one at or before the window's first frame on.
    const auto first_after = std::upper_bound(imu_.begin(), imu_.end(), alignment_frames_.front().t_ns,
                                              [](TimeNs t, const ImuSample& s) { return t < s.t_ns; });
    if (first_after != imu_.begin()) imu_.erase(imu_.begin(), first_after - 1);
    return;
  }
  Vec15 sigma;
  sigma << Vec3::Constant(config_.prior_rotation_sigma_rad), Vec3::Constant(config_.prior_position_sigma_m),
      Vec3::Constant(config_.moving_velocity_sigma_m_s), Vec3::Constant(config_.prior_gyro_bias_sigma_rad_s),
      Vec3::Constant(config_.prior_accel_bias_sigma_m_s2);
  smoother_.initialize(*a.state, sigma, window.front());
  alignment_frames_.clear();
  propagator_.reset(smoother_.newest(), imu_);
  publish_state(window.front(), 0.0);
  for (std::size_t k = 1; k < window.size(); ++k) add_frame(window[k]);
}

void Vio::publish_state(const FrontendOutput& frame, double imu_gap_s) {
  latest_state_ = VioStateOutput{smoother_.newest(), smoother_.newest_covariance(), smoother_.stats().landmarks,
                                 static_cast<int>(frame.matches.size()), imu_gap_s};
  if (on_state_) on_state_(*latest_state_);
}

}  // namespace vilslam
