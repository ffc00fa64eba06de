#include "lidar/degeneracy.h"

#include <Eigen/Eigenvalues>

namespace vilslam::lidar {

Degeneracy analyze_degeneracy(const Mat6& information, double min_eigenvalue) {
  const Eigen::SelfAdjointEigenSolver<Mat6> eigen(0.5 * (information + information.transpose()));
  Degeneracy d;
  d.eigenvalues = eigen.eigenvalues();
  d.eigenvectors = eigen.eigenvectors();
  d.min_max_ratio = d.eigenvalues(5) > 0.0 ? d.eigenvalues(0) / d.eigenvalues(5) : 0.0;
  // With orthonormal eigenvectors V_f^-1 = V_f^T, so V_f^-1 V_u is the projector onto the kept eigenvectors.
  d.well_conditioned_projection.setZero();
  for (int i = 0; i < 6; ++i) {
    const Vec6 v = d.eigenvectors.col(i);
    if (d.eigenvalues(i) < min_eigenvalue) {
      d.degenerate_directions.push_back(v);
    } else {
      d.well_conditioned_projection += v * v.transpose();
    }
  }
  return d;
}

}  // namespace vilslam::lidar
