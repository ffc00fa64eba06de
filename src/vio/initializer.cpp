#include "vio/initializer.h"

#include <cmath>
#include <stdexcept>

namespace vilslam {

Initialization static_initialization(const std::vector<ImuSample>& samples, TimeNs t_ns,
                                     const InitializerConfig& config) {
  const TimeNs t0_ns = t_ns - s_to_ns(config.averaging_window_s);
  Vec3 gyro_sum = Vec3::Zero(), accel_sum = Vec3::Zero();
  Vec3 gyro_sq = Vec3::Zero(), accel_sq = Vec3::Zero();
  int n = 0;
  for (const ImuSample& s : samples) {
    if (s.t_ns < t0_ns || s.t_ns > t_ns) continue;
    gyro_sum += s.gyro_rad_s;
    accel_sum += s.accel_m_s2;
    gyro_sq += s.gyro_rad_s.cwiseAbs2();
    accel_sq += s.accel_m_s2.cwiseAbs2();
    ++n;
  }
  if (n == 0) throw std::invalid_argument("static_initialization: no IMU sample before the first frame");
  const Vec3 gyro_mean = gyro_sum / n;
  const Vec3 accel_mean = accel_sum / n;
  const double accel_std = std::sqrt(std::max(0.0, (accel_sq / n - accel_mean.cwiseAbs2()).sum()));
  const double gyro_std = std::sqrt(std::max(0.0, (gyro_sq / n - gyro_mean.cwiseAbs2()).sum()));

  // At rest the specific force is R_W_I^T (0, 0, g): rotate it onto +z, then remove the yaw (ZYX).
  const Mat3 R_tilt = Quat::FromTwoVectors(accel_mean, Vec3::UnitZ()).toRotationMatrix();
  Initialization init;
  init.state.t_ns = t_ns;
  init.state.R_W_I = so3::rot_z(-so3::yaw_rad(R_tilt)) * R_tilt;
  init.is_static = accel_std <= config.max_accel_std_m_s2 && gyro_std <= config.max_gyro_std_rad_s;
  // Moving (a reset mid-run), the mean rate is the motion's, not the bias: start from 0 and let the prior hold it.
  init.state.bias_gyro_rad_s = init.is_static ? gyro_mean : Vec3::Zero();
  init.samples = n;
  return init;
}

}  // namespace vilslam
