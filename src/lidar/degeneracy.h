#pragma once
// Degeneracy of a registration (Zhang, Kaess & Singh, ICRA 2016): eigen-analysis of the 6x6 information
// matrix J^T J at the solution. Directions whose eigenvalue is below a threshold are poorly constrained; the
// solution remapping keeps the prior motion along them by projecting updates onto the well-conditioned ones.
#include <vector>

#include "common/lie.h"

namespace vilslam::lidar {

struct Degeneracy {
  Vec6 eigenvalues = Vec6::Zero();    // ascending
  Mat6 eigenvectors = Mat6::Identity();  // column i belongs to eigenvalues(i); [rho; phi] ordering
  double min_max_ratio = 0.0;         // smallest / largest eigenvalue
  std::vector<Vec6> degenerate_directions;
  Mat6 well_conditioned_projection = Mat6::Identity();  // Zhang et al. eq. (12): V_f^-1 V_u

  bool degenerate() const { return !degenerate_directions.empty(); }
};

Degeneracy analyze_degeneracy(const Mat6& information, double min_eigenvalue);

}  // namespace vilslam::lidar
