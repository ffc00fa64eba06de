#pragma once
// A small dense Levenberg-Marquardt solver over the window's states. Factors hand it their whitened
// normal-equation contributions (J^T J, J^T r, ||r||^2) on the 15-dimensional blocks of the states
// they touch; the solver knows nothing about IMUs or cameras.
#include <Eigen/Core>
#include <functional>
#include <vector>

#include "vio/window_state.h"

namespace vilslam {

struct LinearFactor {
  std::vector<int> slots;  // window positions of the states touched, in the order of the blocks below
  int block_dim = kStateDim;  // each block covers a state's first block_dim tangent coordinates
  Eigen::MatrixXd H;       // J^T J, (block_dim k) x (block_dim k)
  Eigen::VectorXd g;       // J^T r
  double cost = 0;         // ||r||^2
};

// The factor of a whitened residual r with Jacobian J = [J_slot0, J_slot1, ...], equal-width blocks.
LinearFactor make_linear_factor(std::vector<int> slots, const Eigen::MatrixXd& J, const Eigen::VectorXd& r);
// Adds the factor's blocks into the window's normal equations H dx = -g.
void accumulate(const LinearFactor& f, Eigen::MatrixXd& H, Eigen::VectorXd& g);
double total_cost(const std::vector<LinearFactor>& factors);

struct LmConfig {
  int max_iterations = 10;
  double initial_lambda = 1e-4;       // Marquardt damping: (H + lambda diag(H)) dx = -g
  double min_relative_decrease = 1e-4;  // stop when an accepted step improves the cost by less
  double min_step_norm = 1e-9;
};

struct LmSummary {
  int iterations = 0;
  double initial_cost = 0;
  double final_cost = 0;
  Eigen::MatrixXd H;  // normal matrix at the final estimate (undamped)
};

using Linearizer = std::function<std::vector<LinearFactor>(const std::vector<NavState>&)>;

// Minimizes the sum of the factors' costs over the states, in place.
LmSummary solve_lm(const Linearizer& linearize, std::vector<NavState>& states, const LmConfig& config);

}  // namespace vilslam
