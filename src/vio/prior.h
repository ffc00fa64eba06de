#pragma once
// Prior factors on window states: the initial prior and the Schur-complement marginalization prior
// (paper Sec. "Optimization and marginalization"). The prior keeps its linearization point fixed
// (first-estimate Jacobians): r = r0 + J0 (x [-] x_lin).
#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "vio/dense_lm.h"
#include "vio/window_state.h"

namespace vilslam {

struct PriorFactor {
  std::vector<std::uint64_t> state_ids;  // the states it constrains, in block order
  std::vector<NavState> x_lin;           // their linearization points
  Eigen::MatrixXd J0;                    // whitened, rows x (15 * states)
  Eigen::VectorXd r0;                    // whitened residual at x_lin

  bool empty() const { return state_ids.empty(); }
};

// Residual r0 + J0 (x [-] x_lin) and its Jacobian J0 * blockdiag(d(x [-] x_lin)/dx) at the given states.
struct PriorResidual {
  Eigen::VectorXd r;
  Eigen::MatrixXd J;
};
PriorResidual prior_residual(const PriorFactor& prior, const std::vector<NavState>& states);

// Normal-equation contribution of the prior; slots[k] is the window position of prior.state_ids[k].
LinearFactor prior_linear_factor(const PriorFactor& prior, const std::vector<NavState>& states,
                                 const std::vector<int>& slots);

// Independent Gaussian prior with standard deviations sigma on the tangent of x0.
PriorFactor diagonal_prior(std::uint64_t state_id, const NavState& x0, const Vec15& sigma);

// Schur complement of drop_slot out of the normal equations of `factors` (all linearized at `states`,
// the window; ids[k] names the state at slot k). The result is a prior on the other states the factors
// touch, linearized at their current values: J0^T J0 = H*, J0^T r0 = g*.
PriorFactor marginalize(const std::vector<LinearFactor>& factors, int drop_slot, const std::vector<NavState>& states,
                        const std::vector<std::uint64_t>& ids);

}  // namespace vilslam
