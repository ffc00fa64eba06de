#include "io/ros_convert.h"
#include "io/ros_wire.h"

namespace vilslam {

ImuSample imu_sample_from_ros(const RosImu& imu) {
  ImuSample s;
  s.t_ns = imu.header.stamp_ns;
  s.gyro_rad_s = Vec3(imu.angular_velocity[0], imu.angular_velocity[1], imu.angular_velocity[2]);
  s.accel_m_s2 = Vec3(imu.linear_acceleration[0], imu.linear_acceleration[1], imu.linear_acceleration[2]);
  if (!s.gyro_rad_s.allFinite() || !s.accel_m_s2.allFinite()) throw WireError("non-finite value");
  return s;
}

}  // namespace vilslam
