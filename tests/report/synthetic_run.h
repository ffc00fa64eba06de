#pragma once
// A hand-made `vilslam run --out` folder for the report's command tests (no simulation): 20 s on a circle of
// radius 5 m at 10 Hz, the ground truth as a TUM file, a VIO estimate in a yawed and shifted world with a
// growing error, LiDAR odometry and loop-closed poses, one loop, every 20th sweep degenerate, and the timings
// of a real-time run.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "common/lie.h"
#include "io/trajectory_io.h"

namespace vilslam::test {

constexpr int kSyntheticPoses = 200;
constexpr int kSyntheticDegenerateEvery = 20;

inline Trajectory circle_T_W_B() {
  Trajectory T_W_B;
  for (int i = 0; i < kSyntheticPoses; ++i) {
    const double angle_rad = 2 * M_PI * i / kSyntheticPoses;
    const SE3 T(Quat(Eigen::AngleAxisd(angle_rad + M_PI / 2, Vec3::UnitZ())),
                Vec3(5 * std::cos(angle_rad), 5 * std::sin(angle_rad), 1.0 + 0.2 * std::sin(3 * angle_rad)));
    T_W_B.push_back({1'000'000'000 + static_cast<TimeNs>(i) * 100'000'000, T});
  }
  return T_W_B;
}

// gt moved into another world (T_other_W) with a position error growing to error_m at the end.
inline Trajectory drifted(const Trajectory& gt, const SE3& T_other_W, double error_m) {
  Trajectory est;
  for (std::size_t i = 0; i < gt.size(); ++i) {
    const double f = static_cast<double>(i) / static_cast<double>(gt.size() - 1);
    const SE3 T_W_B(gt[i].T_W_B.quat(), gt[i].T_W_B.translation() + Vec3(error_m * f, 0, 0.5 * error_m * f * f));
    est.push_back({gt[i].t_ns, T_other_W * T_W_B});
  }
  return est;
}

// Writes the run folder into dir and the ground truth to gt_path.
inline void write_synthetic_run(const std::filesystem::path& dir, const std::filesystem::path& gt_path) {
  std::filesystem::create_directories(dir);
  const Trajectory gt = circle_T_W_B();
  write_trajectory(gt_path.string(), gt, TrajectoryFormat::kTum);
  const SE3 T_vio_W(Quat(Eigen::AngleAxisd(0.5, Vec3::UnitZ())), Vec3(1, -2, 0.3));
  write_trajectory((dir / "vio_camera.tum").string(), drifted(gt, T_vio_W, 0.4), TrajectoryFormat::kTum);
  write_trajectory((dir / "lidar.tum").string(), drifted(gt, SE3(), 0.2), TrajectoryFormat::kTum);
  write_trajectory((dir / "lidar_final.tum").string(), drifted(gt, SE3(), 0.05), TrajectoryFormat::kTum);
  std::ofstream(dir / "loops.csv") << "# from_t_ns,to_t_ns,tx,ty,tz,qx,qy,qz,qw\n"
                                   << gt[5].t_ns << ',' << gt[195].t_ns << ",0.1,0,0,0,0,0,1\n";
  std::ofstream degeneracy(dir / "degeneracy.csv");
  degeneracy << "t_ns,degenerate,eig0,eig1,eig2,eig3,eig4,eig5,rms_residual_m,matched_fraction,inlier_fraction\n";
  for (int i = 0; i < kSyntheticPoses; ++i)
    degeneracy << gt[i].t_ns << ',' << (i % kSyntheticDegenerateEvery == 0 ? 1 : 0) << ",1,2,3,4,5,6,0.01,0.9,0.9\n";
  std::ofstream samples(dir / "timing_samples.csv");
  samples << "series,ms\n";
  for (int i = 0; i < kSyntheticPoses; ++i) samples << "frontend," << 5 + i % 10 << "\n";
  for (int i = 0; i < kSyntheticPoses; ++i) samples << "lidar_mapping," << 20 + i % 7 << "\n";
  for (int i = 0; i < kSyntheticPoses; ++i) samples << "imu_pose_latency," << 0.5 + 0.01 * (i % 13) << "\n";
  std::ofstream(dir / "timings.json")
      << "{\n  \"mode\": \"vil\",\n  \"data_s\": 19.9,\n  \"run_wall_s\": 8.5,\n"
      << "  \"frontend\": {\"frames\": 200, \"median_ms\": 9, \"p95_ms\": 14, \"max_ms\": 14},\n"
      << "  \"lidar_mapping\": {\"frames\": 200, \"median_ms\": 23, \"p95_ms\": 26, \"max_ms\": 26},\n"
      << "  \"loops_accepted\": 1,\n"
      << "  \"lidar_lost_t_ns\": [13250000000],\n"
      << "  \"realtime\": {\"speed\": 1.0, \"dropped_sweeps\": 0,\n"
      << "    \"imu_pose_latency\": {\"frames\": 200, \"median_ms\": 0.56, \"p95_ms\": 0.62, \"max_ms\": 0.62}}\n}\n";
}

}  // namespace vilslam::test
