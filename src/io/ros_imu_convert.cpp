// sensor_msgs/Imu and geometry_msgs/PoseStamped to and from the project's samples and states.
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

RosImu ros_imu_from_sample(const ImuSample& s) {
  RosImu m;
  m.header.stamp_ns = s.t_ns;
  m.header.frame_id = "imu0";
  m.orientation_covariance[0] = -1;  // sensor_msgs/Imu: -1 marks "no orientation estimate"
  m.angular_velocity = {s.gyro_rad_s.x(), s.gyro_rad_s.y(), s.gyro_rad_s.z()};
  m.linear_acceleration = {s.accel_m_s2.x(), s.accel_m_s2.y(), s.accel_m_s2.z()};
  return m;
}

RosPoseStamped ros_pose_from_state(const GroundTruthState& s) {
  RosPoseStamped m;
  m.header.stamp_ns = s.t_ns;
  m.header.frame_id = "world";
  const Vec3& p = s.T_W_I.translation();
  const Quat& q = s.T_W_I.quat();
  m.position = {p.x(), p.y(), p.z()};
  m.orientation_xyzw = {q.x(), q.y(), q.z(), q.w()};
  return m;
}

}  // namespace vilslam
