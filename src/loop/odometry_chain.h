#pragma once
// A chain of LiDAR odometry factors between two anchor poses a < b of the global pose graph: composed into one
// relative factor, and, once the anchors are corrected, the chain's interior poses corrected to match them
// (docs/pose_graph.md, "Bounded correction"). First-order propagation on SE(3) in the factors' convention:
// a factor measuring T_meas has residual e = Log(T_meas^-1 T_u^-1 T_v), i.e. T_u^-1 T_v = T_meas Exp(e).
#include <cstddef>
#include <vector>

#include <Eigen/StdVector>

#include "common/lie.h"
#include "common/types.h"

namespace vilslam::loop {

// steps[i] is the measured T_{i-1,i} of pose i (steps[0] is unused), step_covariances[i] its error covariance
// ([rho; phi]). A chain a -> b uses steps a+1 .. b.
using Mat6List = std::vector<Mat6, Eigen::aligned_allocator<Mat6>>;

struct ComposedChain {
  SE3 T_a_b;        // Z_ab = Z_{a,a+1} ... Z_{b-1,b}
  Mat6 covariance;  // C_b of the composed error at b (eq. C1 of docs/pose_graph.md)
};

// The chain a -> b (a < b < steps.size()).
ComposedChain compose_chain(const std::vector<SE3>& steps, const Mat6List& step_covariances, std::size_t a,
                            std::size_t b);

// Moves poses a+1 .. b-1 to T_W_j = T_W_a Z_aj Exp(d_j), the minimum of the chain's factors given the corrected
// T_W_a and T_W_b (eq. C2); poses a and b are read, not written.
void correct_chain_interior(const std::vector<SE3>& steps, const Mat6List& step_covariances, std::size_t a,
                            std::size_t b, Trajectory& poses);

}  // namespace vilslam::loop
