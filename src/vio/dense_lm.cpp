#include "vio/dense_lm.h"

#include <Eigen/Cholesky>
#include <cmath>

namespace vilslam {

LinearFactor make_linear_factor(std::vector<int> slots, const Eigen::MatrixXd& J, const Eigen::VectorXd& r) {
  LinearFactor f;
  f.slots = std::move(slots);
  f.block_dim = static_cast<int>(J.cols() / static_cast<int>(f.slots.size()));
  f.H = J.transpose() * J;
  f.g = J.transpose() * r;
  f.cost = r.squaredNorm();
  return f;
}

namespace {

template <int D>
void accumulate_blocks(const LinearFactor& f, Eigen::MatrixXd& H, Eigen::VectorXd& g) {
  const int k = static_cast<int>(f.slots.size());
  for (int a = 0; a < k; ++a) {
    const int ra = kStateDim * f.slots[a];
    g.segment<D>(ra) += f.g.segment<D>(D * a);
    for (int b = 0; b < k; ++b) H.block<D, D>(ra, kStateDim * f.slots[b]) += f.H.block<D, D>(D * a, D * b);
  }
}

}  // namespace

void accumulate(const LinearFactor& f, Eigen::MatrixXd& H, Eigen::VectorXd& g) {
  // Fixed-size blocks for the two widths the factors use (poses, whole states).
  if (f.block_dim == 6) return accumulate_blocks<6>(f, H, g);
  if (f.block_dim == kStateDim) return accumulate_blocks<kStateDim>(f, H, g);
  const int k = static_cast<int>(f.slots.size());
  const int d = f.block_dim;
  for (int a = 0; a < k; ++a) {
    const int ra = kStateDim * f.slots[a];
    g.segment(ra, d) += f.g.segment(d * a, d);
    for (int b = 0; b < k; ++b) H.block(ra, kStateDim * f.slots[b], d, d) += f.H.block(d * a, d * b, d, d);
  }
}

double total_cost(const std::vector<LinearFactor>& factors) {
  double c = 0;
  for (const LinearFactor& f : factors) c += f.cost;
  return c;
}

namespace {

void build_normal_equations(const std::vector<LinearFactor>& factors, int n, Eigen::MatrixXd& H, Eigen::VectorXd& g) {
  H.setZero(kStateDim * n, kStateDim * n);
  g.setZero(kStateDim * n);
  for (const LinearFactor& f : factors) accumulate(f, H, g);
}

std::vector<NavState> apply_step(const std::vector<NavState>& states, const Eigen::VectorXd& dx) {
  std::vector<NavState> out(states.size());
  for (size_t i = 0; i < states.size(); ++i) out[i] = boxplus(states[i], dx.segment<kStateDim>(kStateDim * i));
  return out;
}

}  // namespace

LmSummary solve_lm(const Linearizer& linearize, std::vector<NavState>& states, const LmConfig& config) {
  const int n = static_cast<int>(states.size());
  LmSummary summary;
  std::vector<LinearFactor> factors = linearize(states);
  double cost = total_cost(factors);
  summary.initial_cost = cost;
  double lambda = config.initial_lambda;
  Eigen::MatrixXd H;
  Eigen::VectorXd g;
  build_normal_equations(factors, n, H, g);
  for (int it = 0; it < config.max_iterations; ++it) {
    summary.iterations = it + 1;
    bool accepted = false;
    double step_norm = 0;
    double decrease = 0;
    for (int attempt = 0; attempt < 10 && !accepted; ++attempt) {
      Eigen::MatrixXd A = H;
      // Marquardt damping with a small floor so that unconstrained directions stay solvable.
      A.diagonal() += lambda * (H.diagonal().array().max(1e-6)).matrix();
      const Eigen::VectorXd dx = A.ldlt().solve(-g);
      step_norm = dx.norm();
      if (!dx.allFinite()) {
        lambda *= 10;
        continue;
      }
      std::vector<NavState> candidate = apply_step(states, dx);
      std::vector<LinearFactor> cand_factors = linearize(candidate);
      const double cand_cost = total_cost(cand_factors);
      if (cand_cost < cost) {
        decrease = (cost - cand_cost) / std::max(cost, 1e-300);
        states = std::move(candidate);
        factors = std::move(cand_factors);
        cost = cand_cost;
        lambda = std::max(lambda / 3, 1e-9);
        accepted = true;
      } else {
        lambda *= 4;
      }
    }
    build_normal_equations(factors, n, H, g);
    if (!accepted || decrease < config.min_relative_decrease || step_norm < config.min_step_norm) break;
  }
  summary.final_cost = cost;
  summary.H = std::move(H);
  return summary;
}

}  // namespace vilslam
