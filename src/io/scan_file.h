#pragma once
// LiDAR scan payload files.
//  - The project's .bin (docs/formats.md): little-endian, 8-byte magic "VLSCAN01", uint32 num_points,
//    uint32 flags (bit 0: has_ring), then per point 24 bytes: float32 x y z intensity t_offset_s,
//    uint16 ring, uint16 zero.
//  - KITTI velodyne .bin: per point float32 x y z reflectance (no ring, no per-point time).
// Readers throw InputError naming the file (missing, wrong magic, truncated, non-finite values).
#include <cstddef>
#include <string>

#include "common/types.h"
#include "io/cloud_io.h"

namespace vilslam {

constexpr std::size_t kScanHeaderBytes = 16;
constexpr std::size_t kScanPointBytes = 24;

// Returns a scan with t_ns = 0 (the time lives in data.csv).
LidarScan read_scan_file(const std::string& path);
// Writes the whole file (no temporary: the dataset writer works inside a partial folder).
void write_scan_file(const std::string& path, const LidarScan& scan);
// Cheap check: magic and header against the file size; returns num_points.
std::size_t check_scan_file(const std::string& path);

// Through read_cloud (cloud_io.h) and scan_from_cloud: a KITTI .bin has no ring and no per-point time.
LidarScan read_kitti_scan(const std::string& path);

// A cloud as a sweep. The cloud's ring field, when present, gives each point's ring (has_ring = true;
// otherwise has_ring = false). Its per-point times, when present, give t_offset_s relative to the earliest
// point, which starts the sweep (t_ns, when 0, becomes that point's time); without them every point is at t_ns.
LidarScan scan_from_cloud(const PointCloud& cloud, TimeNs t_ns = 0);
// Cheap check: the size is a multiple of 16 bytes; returns the number of points.
std::size_t check_kitti_scan(const std::string& path);

}  // namespace vilslam
