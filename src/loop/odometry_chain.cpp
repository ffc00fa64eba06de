// Composition and interior correction of odometry chains (see odometry_chain.h, docs/pose_graph.md).
#include "loop/odometry_chain.h"

#include <Eigen/Cholesky>

namespace vilslam::loop {
namespace {

// C_{j+1} = Ad(Z_j^-1) C_j Ad(Z_j^-1)^T + Sigma: the error of Z_aj carried through Z_j (eq. C1).
Mat6 propagate(const Mat6& C_j, const SE3& Z_j, const Mat6& step_covariance) {
  const Mat6 Ad = Z_j.inverse().adjoint();
  return Ad * C_j * Ad.transpose() + step_covariance;
}

}  // namespace

ComposedChain compose_chain(const std::vector<SE3>& steps, const Mat6List& step_covariances, std::size_t a,
                            std::size_t b) {
  ComposedChain chain{SE3(), Mat6::Zero()};
  for (std::size_t j = a + 1; j <= b; ++j) {
    chain.covariance = propagate(chain.covariance, steps[j], step_covariances[j]);
    chain.T_a_b = chain.T_a_b * steps[j];
  }
  return chain;
}

void correct_chain_interior(const std::vector<SE3>& steps, const Mat6List& step_covariances, std::size_t a,
                            std::size_t b, Trajectory& poses) {
  if (b < a + 2) return;
  // Forward pass: Z_aj and C_j for j = a+1 .. b (index j - a - 1).
  std::vector<SE3> T_a_j;
  Mat6List C;
  T_a_j.reserve(b - a);
  C.reserve(b - a);
  SE3 T = SE3();
  Mat6 C_j = Mat6::Zero();
  for (std::size_t j = a + 1; j <= b; ++j) {
    C_j = propagate(C_j, steps[j], step_covariances[j]);
    T = T * steps[j];
    T_a_j.push_back(T);
    C.push_back(C_j);
  }
  const SE3& T_W_a = poses[a].T_W_B;
  const SE3& Z_ab = T_a_j.back();
  // Misclosure of the chain at b, and g = C_b^-1 e.
  const Vec6 e = (Z_ab.inverse() * (T_W_a.inverse() * poses[b].T_W_B)).log();
  const Vec6 g = C.back().llt().solve(e);
  const SE3 Z_b_a = Z_ab.inverse();
  for (std::size_t j = a + 1; j < b; ++j) {
    const std::size_t k = j - a - 1;
    // d_j = E[e_j | e_b] = C_j Ad(Z_jb^-1)^T C_b^-1 e, with Z_jb^-1 = Z_ab^-1 Z_aj (eq. C2).
    const Vec6 d_j = C[k] * ((Z_b_a * T_a_j[k]).adjoint().transpose() * g);
    poses[j].T_W_B = T_W_a * T_a_j[k] * SE3::exp(d_j);
  }
}

}  // namespace vilslam::loop
