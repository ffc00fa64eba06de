#include "eval/icp.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include "eval/alignment.h"

namespace vilslam::eval {
namespace {

constexpr std::size_t kGrain = 1024;
constexpr std::ptrdiff_t kNoMatch = -1;
using Mat6 = Eigen::Matrix<double, 6, 6>;

// Model index of the nearest neighbour of every moved map point, or kNoMatch beyond max_dist.
// One slot per point, so the parallel loop is deterministic.
std::vector<std::ptrdiff_t> find_matches(const std::vector<Vec3>& moved, const PointIndex& model, double max_dist) {
  std::vector<std::ptrdiff_t> match(moved.size(), kNoMatch);
  const float max_dist_sq = static_cast<float>(max_dist * max_dist);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, moved.size(), kGrain), [&](const auto& range) {
    for (std::size_t i = range.begin(); i != range.end(); ++i) {
      const PointIndex::Neighbour n = model.nearest(moved[i].cast<float>());
      if (n.dist_sq <= max_dist_sq) match[i] = static_cast<std::ptrdiff_t>(n.index);
    }
  });
  return match;
}

struct NormalEquations {
  Mat6 A = Mat6::Zero();
  Vec6 b = Vec6::Zero();
  double sse = 0;
  std::size_t count = 0;
};

// Point-to-plane Gauss-Newton system in x = [omega; dt]: r = n.(p - q) + (p x n).omega + n.dt.
// parallel_deterministic_reduce splits and joins in a fixed order, so the sums are bit-reproducible.
NormalEquations point_to_plane_system(const std::vector<Vec3>& moved, const std::vector<std::ptrdiff_t>& match,
                                      const PointIndex& model, const std::vector<Eigen::Vector3f>& normals) {
  return tbb::parallel_deterministic_reduce(
      tbb::blocked_range<std::size_t>(0, moved.size(), kGrain), NormalEquations{},
      [&](const tbb::blocked_range<std::size_t>& range, NormalEquations acc) {
        for (std::size_t i = range.begin(); i != range.end(); ++i) {
          if (match[i] == kNoMatch) continue;
          const auto j = static_cast<std::size_t>(match[i]);
          const Vec3 n = normals[j].cast<double>();
          const Vec3 q = model.points()[j].cast<double>();
          const double r = n.dot(moved[i] - q);
          Vec6 J;
          J << moved[i].cross(n), n;
          acc.A += J * J.transpose();
          acc.b -= J * r;
          acc.sse += (moved[i] - q).squaredNorm();
          ++acc.count;
        }
        return acc;
      },
      [](NormalEquations x, const NormalEquations& y) {
        x.A += y.A;
        x.b += y.b;
        x.sse += y.sse;
        x.count += y.count;
        return x;
      });
}

// Solves A x = b on the eigen-directions of A with eigenvalue >= min_eigenvalue; x has no component along
// the others (the pseudo-inverse restricted to the constrained subspace). Counts the dropped directions.
Vec6 solve_constrained(const Mat6& A, const Vec6& b, double min_eigenvalue, int* dropped) {
  const Eigen::SelfAdjointEigenSolver<Mat6> eig(A);
  Vec6 x = Vec6::Zero();
  *dropped = 0;
  for (int k = 0; k < 6; ++k) {
    const double lambda = eig.eigenvalues()(k);
    if (lambda < min_eigenvalue) {
      ++*dropped;
      continue;
    }
    const Vec6 v = eig.eigenvectors().col(k);
    x += v * (v.dot(b) / lambda);
  }
  return x;
}

}  // namespace

std::vector<Eigen::Vector3f> estimate_normals(const PointIndex& model, std::size_t neighbours) {
  std::vector<Eigen::Vector3f> normals(model.size(), Eigen::Vector3f::UnitZ());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, model.size(), kGrain), [&](const auto& range) {
    for (std::size_t i = range.begin(); i != range.end(); ++i) {
      const auto nbrs = model.nearest_k(model.points()[i], neighbours);
      if (nbrs.size() < 3) continue;
      Vec3 mean = Vec3::Zero();
      for (const auto& n : nbrs) mean += model.points()[n.index].cast<double>();
      mean /= static_cast<double>(nbrs.size());
      Mat3 cov = Mat3::Zero();
      for (const auto& n : nbrs) {
        const Vec3 d = model.points()[n.index].cast<double>() - mean;
        cov += d * d.transpose();
      }
      normals[i] = Eigen::SelfAdjointEigenSolver<Mat3>(cov).eigenvectors().col(0).cast<float>();
    }
  });
  return normals;
}

IcpResult align_icp(const std::vector<Eigen::Vector3f>& map, const PointIndex& model,
                    const std::vector<Eigen::Vector3f>& model_normals, const IcpConfig& config,
                    const SE3& T_model_map_initial) {
  const bool to_plane = config.mode == IcpMode::kPointToPlane;
  if (to_plane && model_normals.size() != model.size()) throw std::invalid_argument("point-to-plane ICP needs model normals");
  IcpResult result;
  result.T_model_map = T_model_map_initial;
  std::vector<Vec3> moved(map.size());
  for (result.iterations = 1; result.iterations <= config.max_iterations; ++result.iterations) {
    double radius_m = 0;
    for (std::size_t i = 0; i < map.size(); ++i) {
      moved[i] = result.T_model_map * map[i].cast<double>();
      radius_m = std::max(radius_m, moved[i].norm());
    }
    const std::vector<std::ptrdiff_t> match = find_matches(moved, model, config.max_correspondence_m);
    SE3 update;
    if (to_plane) {
      const NormalEquations eq = point_to_plane_system(moved, match, model, model_normals);
      if (eq.count < 6) throw std::invalid_argument("ICP: fewer than 6 correspondences within range");
      const Vec6 x = solve_constrained(eq.A, eq.b, config.min_eigenvalue_per_match * static_cast<double>(eq.count),
                                       &result.degenerate_directions);
      update = SE3(so3::exp_quat(x.head<3>()), x.tail<3>());
      result.inliers = eq.count;
      result.rmse_m = std::sqrt(eq.sse / static_cast<double>(eq.count));
    } else {
      std::vector<Vec3> p_map, p_model;
      for (std::size_t i = 0; i < moved.size(); ++i) {
        if (match[i] == kNoMatch) continue;
        p_map.push_back(moved[i]);
        p_model.push_back(model.points()[static_cast<std::size_t>(match[i])].cast<double>());
      }
      if (p_map.size() < 3) throw std::invalid_argument("ICP: fewer than 3 correspondences within range");
      update = align_positions(p_map, p_model, AlignMode::kSe3).T_gt_est;
      double sse = 0;
      for (std::size_t i = 0; i < p_map.size(); ++i) sse += (p_map[i] - p_model[i]).squaredNorm();
      result.inliers = p_map.size();
      result.rmse_m = std::sqrt(sse / static_cast<double>(p_map.size()));
    }
    result.T_model_map = update * result.T_model_map;
    // Largest displacement of a point by this update (rotation about the origin plus translation).
    const double step_m = update.translation().norm() + so3::log(update.quat()).norm() * radius_m;
    if (step_m < config.convergence_m) {
      result.converged = true;
      break;
    }
  }
  result.iterations = std::min(result.iterations, config.max_iterations);
  return result;
}

}  // namespace vilslam::eval
