#include "sim/camera_rays.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <deque>
#include <mutex>
#include <utility>

#include "common/error.h"

namespace vilslam::sim {
namespace {

constexpr std::size_t kCachedTables = 4;

bool same_intrinsics(const CameraIntrinsics& a, const CameraIntrinsics& b) {
  return a.width_px == b.width_px && a.height_px == b.height_px && a.fx == b.fx && a.fy == b.fy && a.cx == b.cx &&
         a.cy == b.cy && a.distortion == b.distortion && a.distortion_coeffs == b.distortion_coeffs;
}

std::shared_ptr<const RayTable> compute_ray_table(const CameraIntrinsics& intrinsics) {
  auto table = std::make_shared<RayTable>();
  const int w = intrinsics.width_px, h = intrinsics.height_px;
  table->width = w;
  table->height = h;
  table->dir_C.resize(static_cast<std::size_t>(w) * h);
  table->pixel_angle_rad.resize(table->dir_C.size());
  tbb::parallel_for(0, h, [&](int r) {
    for (int c = 0; c < w; ++c) {
      table->dir_C[static_cast<std::size_t>(r) * w + c] = unproject(intrinsics, Eigen::Vector2d(c, r)).cast<float>();
    }
    // Angle between the rays of horizontally neighbouring pixels.
    for (int c = 0; c < w; ++c) {
      const std::size_t i = static_cast<std::size_t>(r) * w + std::min(c, w - 2);
      const Vec3 a = table->dir_C[i].cast<double>(), b = table->dir_C[i + 1].cast<double>();
      table->pixel_angle_rad[static_cast<std::size_t>(r) * w + c] = static_cast<float>(std::atan2(a.cross(b).norm(), a.dot(b)));
    }
  });
  return table;
}

}  // namespace

Eigen::Vector2d distort(const CameraIntrinsics& intrinsics, const Eigen::Vector2d& xy) {
  const std::vector<double>& k = intrinsics.distortion_coeffs;
  const double x = xy.x(), y = xy.y(), r2 = x * x + y * y;
  switch (intrinsics.distortion) {
    case DistortionModel::kNone: return xy;
    case DistortionModel::kRadTan: {
      // Brown-Conrady: radial k1 k2, tangential p1 p2 (OpenCV's model with k3 = 0).
      const double radial = 1 + k[0] * r2 + k[1] * r2 * r2;
      return {x * radial + 2 * k[2] * x * y + k[3] * (r2 + 2 * x * x),
              y * radial + k[2] * (r2 + 2 * y * y) + 2 * k[3] * x * y};
    }
    case DistortionModel::kEquidistant: {
      // Kannala-Brandt: theta_d = theta (1 + k1 theta^2 + k2 theta^4 + k3 theta^6 + k4 theta^8).
      const double r = std::sqrt(r2);
      if (r < 1e-12) return xy;
      const double th = std::atan(r), th2 = th * th;
      const double th_d = th * (1 + th2 * (k[0] + th2 * (k[1] + th2 * (k[2] + th2 * k[3]))));
      return xy * (th_d / r);
    }
  }
  return xy;
}

Eigen::Vector2d undistort(const CameraIntrinsics& intrinsics, const Eigen::Vector2d& xy_distorted) {
  if (intrinsics.distortion == DistortionModel::kNone) return xy_distorted;
  Eigen::Vector2d xy = xy_distorted;
  constexpr double kStep = 1e-7;
  for (int it = 0; it < 30; ++it) {
    const Eigen::Vector2d residual = distort(intrinsics, xy) - xy_distorted;
    if (residual.norm() < 1e-14) break;
    Eigen::Matrix2d J;
    for (int d = 0; d < 2; ++d) {
      Eigen::Vector2d step = Eigen::Vector2d::Zero();
      step[d] = kStep;
      J.col(d) = (distort(intrinsics, xy + step) - distort(intrinsics, xy - step)) / (2 * kStep);
    }
    xy -= J.lu().solve(residual);
  }
  return xy;
}

Eigen::Vector2d project(const CameraIntrinsics& intrinsics, const Vec3& p_C) {
  const Eigen::Vector2d d = distort(intrinsics, p_C.head<2>() / p_C.z());
  return {intrinsics.fx * d.x() + intrinsics.cx, intrinsics.fy * d.y() + intrinsics.cy};
}

Vec3 unproject(const CameraIntrinsics& intrinsics, const Eigen::Vector2d& px) {
  const Eigen::Vector2d d((px.x() - intrinsics.cx) / intrinsics.fx, (px.y() - intrinsics.cy) / intrinsics.fy);
  const Eigen::Vector2d xy = undistort(intrinsics, d);
  return Vec3(xy.x(), xy.y(), 1.0).normalized();
}

void check_intrinsics(const CameraIntrinsics& intrinsics) {
  const std::string source = "camera intrinsics";
  if (intrinsics.width_px < 2 || intrinsics.height_px < 2) throw InputError(source, "image must be at least 2 x 2 pixels");
  if (!(intrinsics.fx > 0) || !(intrinsics.fy > 0) || !std::isfinite(intrinsics.fx) || !std::isfinite(intrinsics.fy))
    throw InputError(source, "focal lengths must be positive and finite");
  if (!std::isfinite(intrinsics.cx) || !std::isfinite(intrinsics.cy)) throw InputError(source, "principal point is not finite");
  if (intrinsics.distortion != DistortionModel::kNone) {
    if (intrinsics.distortion_coeffs.size() != 4) throw InputError(source, "distortion needs 4 coefficients");
    for (double k : intrinsics.distortion_coeffs) {
      if (!std::isfinite(k)) throw InputError(source, "distortion coefficient is not finite");
    }
  }
}

std::shared_ptr<const RayTable> ray_table(const CameraIntrinsics& intrinsics) {
  check_intrinsics(intrinsics);
  static std::mutex mutex;
  static std::deque<std::pair<CameraIntrinsics, std::shared_ptr<const RayTable>>> cache;
  std::lock_guard<std::mutex> lock(mutex);
  for (const auto& [key, table] : cache) {
    if (same_intrinsics(key, intrinsics)) return table;
  }
  auto table = compute_ray_table(intrinsics);
  cache.emplace_front(intrinsics, table);
  if (cache.size() > kCachedTables) cache.pop_back();
  return table;
}

SE3 camera_pose_looking(const Vec3& p_W, const Vec3& forward_W) {
  const Vec3 z = forward_W.normalized();
  const Vec3 x = z.cross(Vec3::UnitZ()).normalized();  // right: forward x up
  const Vec3 y = z.cross(x);                            // down
  Mat3 R_W_C;
  R_W_C << x, y, z;
  return SE3(R_W_C, p_W);
}

}  // namespace vilslam::sim
