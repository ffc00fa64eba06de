#pragma once
// The sensor data model: small value types that flow between modules.
#include <opencv2/core.hpp>
#include <cstdint>
#include <vector>

#include "common/lie.h"
#include "common/time.h"

namespace vilslam {

// One IMU sample in the IMU frame I.
struct ImuSample {
  TimeNs t_ns = 0;
  Vec3 gyro_rad_s = Vec3::Zero();     // angular rate
  Vec3 accel_m_s2 = Vec3::Zero();     // specific force
};

// A synchronized stereo pair (8-bit grey images; left = cam0, right = cam1).
struct StereoFrame {
  TimeNs t_ns = 0;
  cv::Mat left;
  cv::Mat right;
};

// One LiDAR return in the LiDAR frame L at the instant it was measured.
struct LidarPoint {
  float x = 0, y = 0, z = 0;
  float intensity = 0;
  float t_offset_s = 0;  // time since the scan's t_ns (start of the sweep), seconds
  std::uint16_t ring = 0;
};

// One LiDAR sweep; t_ns is the time of its first point, every point carries its own offset.
struct LidarScan {
  TimeNs t_ns = 0;
  std::vector<LidarPoint> points;
  bool has_ring = true;  // false when the source gave no ring field (derive it from elevation)
  TimeNs end_t_ns() const;
};

// A timestamped pose T_W_B of some body frame B.
struct TimedPose {
  TimeNs t_ns = 0;
  SE3 T_W_B;
};

// Ground-truth state of the IMU body (EuRoC state_groundtruth_estimate0 columns).
struct GroundTruthState {
  TimeNs t_ns = 0;
  SE3 T_W_I;
  Vec3 v_W_m_s = Vec3::Zero();
  Vec3 bias_gyro_rad_s = Vec3::Zero();
  Vec3 bias_accel_m_s2 = Vec3::Zero();
};

using Trajectory = std::vector<TimedPose>;

// The pose of a time-sorted trajectory at t_ns, interpolated between its neighbours (common/lie.h
// interpolate), held at the first or last pose outside the trajectory's span. Needs a non-empty trajectory.
SE3 pose_at(const Trajectory& poses, TimeNs t_ns);

}  // namespace vilslam
