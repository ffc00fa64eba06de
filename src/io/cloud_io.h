#pragma once
// Point clouds in and out: binary (and ASCII on read) PLY and PCD (also PCL binary_compressed on read)
// with fields x y z and optional intensity, ring, time; KITTI velodyne .bin (x y z reflectance float32).
#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace vilslam {

struct PointCloud {
  std::vector<Eigen::Vector3f> points;
  std::vector<float> intensity;     // empty or one per point
  std::vector<std::uint16_t> ring;  // empty or one per point: the laser of a spinning LiDAR (field "ring")
  std::vector<double> time_s;       // empty or one per point: its time as the file gives it, seconds
                                    // (field "timestamp", e.g. absolute Unix time, or "time")
  std::size_t size() const { return points.size(); }
};

// Reads .ply, .pcd (DATA ascii, binary or binary_compressed) or .bin by extension, with x y z and, when
// present, intensity, ring and time. Throws InputError naming the file on any problem (missing, unknown
// extension, bad header, truncated or corrupt payload, non-finite coordinates or times, ring not in 0..65535).
PointCloud read_cloud(const std::string& path);

// Writes by extension (.ply binary little-endian, .pcd binary), fields x y z intensity. Writes to a temporary file in the
// same folder and renames it, so a failed write never leaves a half-written file.
void write_cloud(const std::string& path, const PointCloud& cloud);

}  // namespace vilslam
