#pragma once
// Point clouds in and out: binary (and ASCII on read) PLY and PCD with fields x y z intensity at least,
// and KITTI velodyne .bin (x y z reflectance float32).
#include <string>
#include <vector>

#include <Eigen/Core>

namespace vilslam {

struct PointCloud {
  std::vector<Eigen::Vector3f> points;
  std::vector<float> intensity;  // empty or one per point
  std::size_t size() const { return points.size(); }
};

// Reads .ply, .pcd or .bin by extension. Throws InputError naming the file on any problem
// (missing, unknown extension, bad header, truncated payload, non-finite coordinates).
PointCloud read_cloud(const std::string& path);

// Writes by extension (.ply binary little-endian, .pcd binary). Writes to a temporary file in the
// same folder and renames it, so a failed write never leaves a half-written file.
void write_cloud(const std::string& path, const PointCloud& cloud);

}  // namespace vilslam
