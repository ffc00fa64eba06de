#pragma once
// The global pose graph of the paper ("Lidar enhanced loop closure", Global pose graph optimization):
// the variables are the LiDAR mapping poses L_k = T_W_L, the factors are LiDAR odometry (between consecutive
// scans) and loop constraints (key scan u -> current scan v), both measuring (L_u)^-1 L_v.
// Solved with Ceres (Levenberg-Marquardt); each pose is a 6-DoF manifold (unit quaternion x R^3), the first
// pose is held fixed as the gauge. The paper uses iSAM2 incrementally; here every optimize() is a batch
// re-optimization warm-started from the previous solution (docs/pose_graph.md).
#include <cstddef>
#include <vector>

#include "common/lie.h"
#include "common/time.h"
#include "common/types.h"

namespace vilslam::loop {

enum class ConstraintKind { kOdometry, kLoop };

// Measurement T_from_to of (T_W_from)^-1 T_W_to. information is 6x6 in the [rho; phi] order of common/lie.h.
struct RelativePoseConstraint {
  std::size_t from_index = 0;
  std::size_t to_index = 0;
  SE3 T_from_to;
  Mat6 information = Mat6::Identity();
  ConstraintKind kind = ConstraintKind::kOdometry;
};

// Gravity tilt of one pose (loop/tilt_factor.h): its up direction R_W_L^T e_z measured as up_L (e.g. by the VIO).
struct TiltConstraint {
  std::size_t index = 0;
  Vec3 up_L = Vec3::UnitZ();
  double sigma_rad = 0.01;
};

enum class RobustLoss { kNone, kHuber, kCauchy };

struct PoseGraphOptions {
  RobustLoss loop_loss = RobustLoss::kHuber;  // applied to loop factors only
  double loop_loss_scale = 1.0;                // in whitened units (sigmas)
  int max_iterations = 100;
  // Odometry factors whose measured translation is at least this long (m) compare it as a length and a bearing
  // (RelativePoseFactor); 0 = none.
  double bearing_min_step_m = 0.0;
  double function_tolerance = 1e-12;
  double gradient_tolerance = 1e-14;
  double parameter_tolerance = 1e-12;
};

// Residuals of one kind of factor at the solution. "whitened" is sqrt(r^T Info r) of r = Log(T_meas^-1 T_u^-1 T_v).
struct ResidualStats {
  std::size_t count = 0;
  double whitened_rms = 0.0;
  double whitened_max = 0.0;
  double translation_max_m = 0.0;
  double rotation_max_rad = 0.0;
};

struct PoseGraphSummary {
  int iterations = 0;
  double initial_cost = 0.0;  // Ceres cost (1/2 sum of robustified squared whitened residuals)
  double final_cost = 0.0;
  bool converged = false;
  ResidualStats odometry;
  ResidualStats loop;
};

class PoseGraph {
 public:
  // Returns the index of the new pose. t_ns is carried to the output only. A fixed pose is held at T_W_L
  // (pose 0 always is: the gauge); more fixed poses are known ones, e.g. a loaded map's.
  std::size_t add_pose(TimeNs t_ns, const SE3& T_W_L, bool fixed = false);
  // Throws std::invalid_argument on an index out of range, from == to, or an information matrix that is
  // not symmetric positive definite.
  void add_constraint(const RelativePoseConstraint& constraint);
  // Throws std::invalid_argument on an index out of range, a non-positive sigma or a non-finite or zero up_L.
  void add_tilt(const TiltConstraint& tilt);

  // Optimizes all poses from their current values; pose 0 and the fixed ones stay.
  PoseGraphSummary optimize(const PoseGraphOptions& options = {});

  const Trajectory& poses() const { return poses_; }
  const std::vector<RelativePoseConstraint>& constraints() const { return constraints_; }

 private:
  Trajectory poses_;
  std::vector<bool> fixed_;
  std::vector<RelativePoseConstraint> constraints_;
  std::vector<TiltConstraint> tilts_;
};

// Throws std::invalid_argument on an index not below pose_count, from == to, or an information matrix that is not
// symmetric positive definite (what PoseGraph::add_constraint checks).
void check_constraint(const RelativePoseConstraint& constraint, std::size_t pose_count);

// Whitened residual r = sqrt(Info) Log(T_meas^-1 (T_W_u^-1 T_W_v)), as the optimizer evaluates it.
Vec6 whitened_residual(const RelativePoseConstraint& c, const SE3& T_W_u, const SE3& T_W_v);

// Odometry constraints between consecutive poses of a trajectory, measured from the trajectory itself.
std::vector<RelativePoseConstraint> odometry_constraints(const Trajectory& poses, const Mat6& information);

// Diagonal information of independent translation (m) and rotation (rad) standard deviations.
Mat6 information_from_sigmas(double sigma_m, double sigma_rad);

}  // namespace vilslam::loop
