// Global pose graph optimization with Ceres (see pose_graph.h).
#include "loop/pose_graph.h"

#include <ceres/ceres.h>
#include <ceres/product_manifold.h>

#include <array>
#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>

#include "loop/relative_pose_factor.h"
#include "loop/tilt_factor.h"

namespace vilslam::loop {
namespace {

using PoseBlock = std::array<double, kPoseBlockSize>;

PoseBlock to_block(const SE3& T) {
  const Quat& q = T.quat();
  const Vec3& t = T.translation();
  return {q.x(), q.y(), q.z(), q.w(), t.x(), t.y(), t.z()};
}

SE3 from_block(const PoseBlock& b) { return SE3(Quat(b[3], b[0], b[1], b[2]), Vec3(b[4], b[5], b[6])); }

// Upper-triangular U with U^T U = information (Cholesky); throws unless symmetric positive definite.
Mat6 sqrt_information(const Mat6& information) {
  if (!information.allFinite() || !information.isApprox(information.transpose(), 1e-9)) {
    throw std::invalid_argument("pose graph: information matrix is not finite and symmetric");
  }
  const Eigen::LLT<Mat6> llt(information);
  if (llt.info() != Eigen::Success) throw std::invalid_argument("pose graph: information matrix is not positive definite");
  return llt.matrixU();
}

std::unique_ptr<ceres::LossFunction> make_loss(RobustLoss loss, double scale) {
  switch (loss) {
    case RobustLoss::kHuber:
      return std::make_unique<ceres::HuberLoss>(scale);
    case RobustLoss::kCauchy:
      return std::make_unique<ceres::CauchyLoss>(scale);
    case RobustLoss::kNone:
      break;
  }
  return nullptr;
}

ResidualStats residual_stats(const Trajectory& poses, const std::vector<RelativePoseConstraint>& constraints,
                             ConstraintKind kind) {
  ResidualStats s;
  double sum_sq = 0.0;
  for (const RelativePoseConstraint& c : constraints) {
    if (c.kind != kind) continue;
    const SE3& T_W_u = poses[c.from_index].T_W_B;
    const SE3& T_W_v = poses[c.to_index].T_W_B;
    const Vec6 xi = (c.T_from_to.inverse() * (T_W_u.inverse() * T_W_v)).log();
    const double whitened = whitened_residual(c, T_W_u, T_W_v).norm();
    ++s.count;
    sum_sq += whitened * whitened;
    s.whitened_max = std::max(s.whitened_max, whitened);
    s.translation_max_m = std::max(s.translation_max_m, xi.head<3>().norm());
    s.rotation_max_rad = std::max(s.rotation_max_rad, xi.tail<3>().norm());
  }
  if (s.count > 0) s.whitened_rms = std::sqrt(sum_sq / static_cast<double>(s.count));
  return s;
}

}  // namespace

std::size_t PoseGraph::add_pose(TimeNs t_ns, const SE3& T_W_L, bool fixed) {
  poses_.push_back({t_ns, T_W_L});
  fixed_.push_back(fixed || poses_.size() == 1);
  return poses_.size() - 1;
}

void PoseGraph::add_constraint(const RelativePoseConstraint& constraint) {
  check_constraint(constraint, poses_.size());
  constraints_.push_back(constraint);
}

void PoseGraph::add_tilt(const TiltConstraint& tilt) {
  if (tilt.index >= poses_.size()) {
    throw std::invalid_argument("pose graph: tilt factor on pose " + std::to_string(tilt.index) + ", not added (" +
                                std::to_string(poses_.size()) + " poses)");
  }
  if (!(tilt.sigma_rad > 0.0) || !std::isfinite(tilt.sigma_rad) || !tilt.up_L.allFinite() || tilt.up_L.norm() < 1e-9) {
    throw std::invalid_argument("pose graph: tilt factor needs a positive sigma and a finite, non-zero up direction");
  }
  tilts_.push_back(tilt);
}

PoseGraphSummary PoseGraph::optimize(const PoseGraphOptions& options) {
  PoseGraphSummary summary;
  if (poses_.empty()) return summary;
  std::vector<PoseBlock> blocks;
  blocks.reserve(poses_.size());
  for (const TimedPose& p : poses_) blocks.push_back(to_block(p.T_W_B));

  ceres::Problem::Options problem_options;
  problem_options.manifold_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  ceres::Problem problem(problem_options);
  ceres::ProductManifold<ceres::EigenQuaternionManifold, ceres::EuclideanManifold<3>> pose_manifold;
  for (PoseBlock& b : blocks) problem.AddParameterBlock(b.data(), kPoseBlockSize, &pose_manifold);
  for (const RelativePoseConstraint& c : constraints_) {
    auto* cost = new ceres::AutoDiffCostFunction<RelativePoseFactor, 6, kPoseBlockSize, kPoseBlockSize>(
        new RelativePoseFactor(c.T_from_to, sqrt_information(c.information),
                               options.bearing_min_step_m > 0.0 && c.kind == ConstraintKind::kOdometry &&
                                   c.T_from_to.translation().norm() >= options.bearing_min_step_m));
    ceres::LossFunction* loss =
        c.kind == ConstraintKind::kLoop ? make_loss(options.loop_loss, options.loop_loss_scale).release() : nullptr;
    problem.AddResidualBlock(cost, loss, blocks[c.from_index].data(), blocks[c.to_index].data());
  }
  for (const TiltConstraint& t : tilts_) {
    problem.AddResidualBlock(
        new ceres::AutoDiffCostFunction<TiltFactor, 3, kPoseBlockSize>(new TiltFactor(t.up_L, t.sigma_rad)), nullptr,
        blocks[t.index].data());
  }
  for (std::size_t i = 0; i < blocks.size(); ++i) {
    if (fixed_[i]) problem.SetParameterBlockConstant(blocks[i].data());
  }

  ceres::Solver::Options solver_options;
  solver_options.minimizer_type = ceres::TRUST_REGION;
  solver_options.trust_region_strategy_type = ceres::LEVENBERG_MARQUARDT;
  solver_options.linear_solver_type = ceres::SPARSE_NORMAL_CHOLESKY;
  solver_options.num_threads = 1;  // a single-threaded solve keeps the result bit-identical
  solver_options.max_num_iterations = options.max_iterations;
  solver_options.function_tolerance = options.function_tolerance;
  solver_options.gradient_tolerance = options.gradient_tolerance;
  solver_options.parameter_tolerance = options.parameter_tolerance;
  solver_options.logging_type = ceres::SILENT;
  ceres::Solver::Summary ceres_summary;
  ceres::Solve(solver_options, &problem, &ceres_summary);

  for (std::size_t i = 0; i < poses_.size(); ++i) poses_[i].T_W_B = from_block(blocks[i]);
  summary.iterations = static_cast<int>(ceres_summary.iterations.size()) - 1;
  summary.initial_cost = ceres_summary.initial_cost;
  summary.final_cost = ceres_summary.final_cost;
  summary.converged = ceres_summary.termination_type == ceres::CONVERGENCE;
  summary.odometry = residual_stats(poses_, constraints_, ConstraintKind::kOdometry);
  summary.loop = residual_stats(poses_, constraints_, ConstraintKind::kLoop);
  return summary;
}

void check_constraint(const RelativePoseConstraint& constraint, std::size_t pose_count) {
  if (constraint.from_index >= pose_count || constraint.to_index >= pose_count) {
    throw std::invalid_argument("pose graph: constraint " + std::to_string(constraint.from_index) + " -> " +
                                std::to_string(constraint.to_index) + " refers to a pose not added (" +
                                std::to_string(pose_count) + " poses)");
  }
  if (constraint.from_index == constraint.to_index) {
    throw std::invalid_argument("pose graph: constraint from a pose to itself");
  }
  sqrt_information(constraint.information);
}

Vec6 whitened_residual(const RelativePoseConstraint& c, const SE3& T_W_u, const SE3& T_W_v) {
  const PoseBlock u = to_block(T_W_u);
  const PoseBlock v = to_block(T_W_v);
  Vec6 r;
  RelativePoseFactor(c.T_from_to, sqrt_information(c.information))(u.data(), v.data(), r.data());
  return r;
}

std::vector<RelativePoseConstraint> odometry_constraints(const Trajectory& poses, const Mat6& information) {
  std::vector<RelativePoseConstraint> constraints;
  for (std::size_t i = 1; i < poses.size(); ++i) {
    constraints.push_back({i - 1, i, poses[i - 1].T_W_B.inverse() * poses[i].T_W_B, information,
                           ConstraintKind::kOdometry});
  }
  return constraints;
}

Mat6 information_from_sigmas(double sigma_m, double sigma_rad) {
  if (!(sigma_m > 0.0) || !(sigma_rad > 0.0) || !std::isfinite(sigma_m) || !std::isfinite(sigma_rad)) {
    throw std::invalid_argument("pose graph: sigmas must be positive and finite");
  }
  Vec6 diag;
  diag << Vec3::Constant(1.0 / (sigma_m * sigma_m)), Vec3::Constant(1.0 / (sigma_rad * sigma_rad));
  return diag.asDiagonal();
}

}  // namespace vilslam::loop
