#pragma once
// LiDAR sweeps in the KITTI odometry layout, so LiDAR-only systems run on the simulated scans:
//   velodyne/NNNNNN.bin  float32 x y z reflectance per point, in L at the point's own instant
//   times.txt            seconds since the first sweep, one line per sweep
//   poses.txt            T_L0_Lk (3x4 row-major) of each sweep's start, in the first sweep's LiDAR frame
//   calib.txt            P0..P3 (the stereo intrinsics and baseline; P2/P3 repeat P0/P1) and Tr = identity:
//                        the folder's reference frame is L, so that poses, scans and Tr agree for LiDAR
//                        tools (they map poses by Tr^-1 P Tr) and for open_dataset. The true camera-LiDAR
//                        extrinsics are in the dataset's rig.yaml.
#include <string>
#include <vector>

#include "common/calibration.h"
#include "common/types.h"

namespace vilslam::sim {

class KittiWriter {
 public:
  // Creates dir/velodyne (dir must not exist yet: the caller writes into a temporary place).
  KittiWriter(std::string dir, const RigCalibration& calib);
  // T_W_L: the LiDAR pose at scan.t_ns (the sweep's first point).
  void add_scan(const LidarScan& scan, const SE3& T_W_L);
  // Writes times.txt, poses.txt and calib.txt.
  void finish() const;

 private:
  std::string dir_;
  RigCalibration calib_;
  std::vector<TimeNs> times_ns_;
  std::vector<SE3> poses_W_L_;
};

}  // namespace vilslam::sim
