#pragma once
// The camera model of the renderer: pinhole with radial-tangential or equidistant distortion (as in
// EuRoC / Kalibr calibrations), the per-pixel ray directions of an intrinsics, and a camera pose helper.
// Pixel coordinates put the centre of pixel (c, r) at (c, r).
#include <memory>
#include <vector>

#include <Eigen/Core>

#include "common/calibration.h"
#include "common/lie.h"

namespace vilslam::sim {

// Distorted normalized coordinates of the undistorted normalized point xy = (x/z, y/z).
Eigen::Vector2d distort(const CameraIntrinsics& intrinsics, const Eigen::Vector2d& xy);
// Inverse of distort by Newton's method.
Eigen::Vector2d undistort(const CameraIntrinsics& intrinsics, const Eigen::Vector2d& xy_distorted);
// Pixel of a point in the camera frame (z > 0).
Eigen::Vector2d project(const CameraIntrinsics& intrinsics, const Vec3& p_C);
// Unit ray in the camera frame through a pixel.
Vec3 unproject(const CameraIntrinsics& intrinsics, const Eigen::Vector2d& px);

// Throws InputError("camera intrinsics", ...) when the intrinsics cannot be rendered (sizes, focal
// lengths, coefficient count, non-finite values).
void check_intrinsics(const CameraIntrinsics& intrinsics);

// Unit ray direction in C of every pixel (row-major) and the angle one pixel subtends there.
struct RayTable {
  int width = 0, height = 0;
  std::vector<Eigen::Vector3f> dir_C;
  std::vector<float> pixel_angle_rad;
};
// The table of these intrinsics, computed once and shared (thread-safe; a few recent ones are kept).
std::shared_ptr<const RayTable> ray_table(const CameraIntrinsics& intrinsics);

// Camera pose T_W_C at p_W whose optical axis (z_C) points along forward_W, x_C to the right and
// y_C down with respect to the world's z-up (forward_W must not be vertical).
SE3 camera_pose_looking(const Vec3& p_W, const Vec3& forward_W);

}  // namespace vilslam::sim
