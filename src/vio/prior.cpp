#include "vio/prior.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <map>

namespace vilslam {

PriorResidual prior_residual(const PriorFactor& prior, const std::vector<NavState>& states) {
  const int k = static_cast<int>(prior.state_ids.size());
  Eigen::VectorXd dx(kStateDim * k);
  Eigen::MatrixXd D = Eigen::MatrixXd::Zero(kStateDim * k, kStateDim * k);
  for (int a = 0; a < k; ++a) {
    dx.segment<kStateDim>(kStateDim * a) = boxminus(states[a], prior.x_lin[a]);
    D.block<kStateDim, kStateDim>(kStateDim * a, kStateDim * a) = boxminus_jacobian(states[a], prior.x_lin[a]);
  }
  return {prior.r0 + prior.J0 * dx, prior.J0 * D};
}

LinearFactor prior_linear_factor(const PriorFactor& prior, const std::vector<NavState>& states,
                                 const std::vector<int>& slots) {
  std::vector<NavState> touched;
  for (int s : slots) touched.push_back(states[s]);
  const PriorResidual res = prior_residual(prior, touched);
  return make_linear_factor(slots, res.J, res.r);
}

PriorFactor diagonal_prior(std::uint64_t state_id, const NavState& x0, const Vec15& sigma) {
  PriorFactor p;
  p.state_ids = {state_id};
  p.x_lin = {x0};
  p.J0 = sigma.cwiseInverse().asDiagonal();
  p.r0 = Eigen::VectorXd::Zero(kStateDim);
  return p;
}

PriorFactor marginalize(const std::vector<LinearFactor>& factors, int drop_slot, const std::vector<NavState>& states,
                        const std::vector<std::uint64_t>& ids) {
  // Local ordering: the dropped state first, then the kept ones by window position.
  std::map<int, int> local;
  local[drop_slot] = 0;
  for (const LinearFactor& f : factors) {
    for (int s : f.slots) local.emplace(s, 0);
  }
  std::vector<int> kept;
  for (auto& [slot, index] : local) {
    if (slot != drop_slot) {
      index = static_cast<int>(kept.size()) + 1;
      kept.push_back(slot);
    }
  }
  const int n = static_cast<int>(local.size());
  Eigen::MatrixXd H = Eigen::MatrixXd::Zero(kStateDim * n, kStateDim * n);
  Eigen::VectorXd g = Eigen::VectorXd::Zero(kStateDim * n);
  for (const LinearFactor& f : factors) {
    LinearFactor remapped = f;
    for (int& s : remapped.slots) s = local.at(s);
    accumulate(remapped, H, g);
  }
  const int m = kStateDim;
  const int r = kStateDim * (n - 1);
  // Schur complement (Sibley et al.): H* = Hrr - Hrm Hmm^-1 Hmr, g* = gr - Hrm Hmm^-1 gm.
  const Eigen::MatrixXd Hmm = 0.5 * (H.topLeftCorner(m, m) + H.topLeftCorner(m, m).transpose());
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig_m(Hmm);
  const Eigen::VectorXd lm = eig_m.eigenvalues();
  const double tol_m = 1e-12 * std::max(lm.maxCoeff(), 1e-300);
  const Eigen::VectorXd lm_inv = (lm.array() > tol_m).select(lm.cwiseInverse(), 0.0);
  const Eigen::MatrixXd Hmm_inv = eig_m.eigenvectors() * lm_inv.asDiagonal() * eig_m.eigenvectors().transpose();
  const Eigen::MatrixXd Hrm = H.bottomLeftCorner(r, m);
  Eigen::MatrixXd H_star = H.bottomRightCorner(r, r) - Hrm * Hmm_inv * Hrm.transpose();
  const Eigen::VectorXd g_star = g.tail(r) - Hrm * Hmm_inv * g.head(m);
  H_star = 0.5 * (H_star + H_star.transpose());

  // H* = V S V^T -> J0 = S^1/2 V^T, r0 = S^-1/2 V^T g* on the directions with positive information.
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(H_star);
  const Eigen::VectorXd s = eig.eigenvalues();
  const double tol = 1e-10 * std::max(s.maxCoeff(), 1e-300);
  std::vector<int> keep;
  for (int i = 0; i < s.size(); ++i) {
    if (s[i] > tol) keep.push_back(i);
  }
  PriorFactor prior;
  prior.J0.resize(static_cast<int>(keep.size()), r);
  prior.r0.resize(static_cast<int>(keep.size()));
  for (size_t row = 0; row < keep.size(); ++row) {
    const int i = keep[row];
    const double sq = std::sqrt(s[i]);
    prior.J0.row(row) = sq * eig.eigenvectors().col(i).transpose();
    prior.r0[row] = eig.eigenvectors().col(i).dot(g_star) / sq;
  }
  for (int slot : kept) {
    prior.state_ids.push_back(ids[slot]);
    prior.x_lin.push_back(states[slot]);
  }
  return prior;
}

}  // namespace vilslam
