#include "sim/scan_degeneracy.h"

#include <Eigen/Eigenvalues>

#include "sim/lidar_beams.h"

namespace vilslam::sim {

ScanDegeneracy analyze_scan_degeneracy(const World& world, const LidarSimConfig& config, const SE3& T_W_L) {
  check_lidar_config(config);
  ScanDegeneracy out;
  const int columns = num_columns(config), beams = beams_per_column(config);
  for (int k = 0; k < columns; ++k) {
    for (int beam = 0; beam < beams; ++beam) {
      const Vec3 dir_W = T_W_L.quat() * beam_direction_L(config, beam, k);
      const auto hit = world.raycast(T_W_L.translation(), dir_W, config.max_range_m);
      if (!hit || hit->range_m < config.min_range_m) continue;
      const Vec3 p = hit->range_m * dir_W;
      Vec6 J;
      J << hit->normal_W, p.cross(hit->normal_W);
      out.information += J * J.transpose();
      ++out.num_points;
    }
  }
  const Eigen::SelfAdjointEigenSolver<Mat6> eigen(out.information);
  out.eigenvalues = eigen.eigenvalues();
  out.eigenvectors = eigen.eigenvectors();
  out.min_max_ratio = out.eigenvalues(5) > 0 ? out.eigenvalues(0) / out.eigenvalues(5) : 0.0;
  out.weakest_direction = out.eigenvectors.col(0);
  return out;
}

}  // namespace vilslam::sim
