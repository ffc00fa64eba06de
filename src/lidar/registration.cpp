#include "lidar/registration.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

namespace vilslam::lidar {

namespace {

struct Correspondences {
  std::vector<EdgeCorrespondence> edges;
  std::vector<PlaneCorrespondence> planes;
};

// Matches every source point in parallel into its own slot, then compacts in index order (deterministic).
template <typename Match, typename Associate>
std::vector<Match> match_all(const std::vector<FeaturePoint>& points_L, const SE3& T_W_L, Associate associate) {
  std::vector<std::optional<Match>> slots(points_L.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, points_L.size(), 64), [&](const auto& range) {
    for (std::size_t i = range.begin(); i != range.end(); ++i) slots[i] = associate(points_L[i], T_W_L * points_L[i].p_L);
  });
  std::vector<Match> matches;
  for (const auto& slot : slots) {
    if (slot) matches.push_back(*slot);
  }
  return matches;
}

// The tilt prior (registration.h): the prior's up direction in L and the weight of its squared residual.
struct TiltPrior {
  Vec3 up_L;
  double weight;
};

std::optional<TiltPrior> tilt_prior(const std::optional<Vec3>& up_L_prior, double up_L_prior_sigma_rad,
                                   const RegistrationConfig& config) {
  if (!up_L_prior || config.tilt_prior_sigma_rad <= 0.0) return std::nullopt;
  const double ratio = config.loss_scale_m / std::max(config.tilt_prior_sigma_rad, up_L_prior_sigma_rad);
  return TiltPrior{*up_L_prior, ratio * ratio};
}

Correspondences associate(const std::vector<FeaturePoint>& edges_L, const std::vector<FeaturePoint>& surfaces_L,
                          const FeatureMap& map, const SE3& T_W_L, const AssociationConfig& config) {
  Correspondences c;
  c.edges = match_all<EdgeCorrespondence>(edges_L, T_W_L, [&](const FeaturePoint& f, const Vec3& p_W) {
    return associate_edge(f.p_L, p_W, map.edges, config);
  });
  c.planes = match_all<PlaneCorrespondence>(surfaces_L, T_W_L, [&](const FeaturePoint& f, const Vec3& p_W) {
    return associate_plane(f.p_L, p_W, map.surfaces, config, T_W_L.rotation() * f.normal_L);
  });
  return c;
}

// rho(s) and its derivative (the IRLS weight) for a squared residual s.
struct Robust {
  double cost;
  double weight;
};

Robust robustify(double s, RobustLoss loss, double scale) {
  const double c2 = scale * scale;
  if (loss == RobustLoss::kCauchy) return {c2 * std::log1p(s / c2), 1.0 / (1.0 + s / c2)};
  if (s <= c2) return {s, 1.0};
  const double r = std::sqrt(s);
  return {2.0 * scale * r - c2, scale / r};
}

// The robustified normal equations H delta = -g of the residuals at T_W_L (IRLS), and the cost sum rho; the
// tilt prior enters H, g and the cost, not the point statistics (sum_sq, inliers, residuals).
struct LinearSystem {
  Mat6 H = Mat6::Zero();
  Vec6 g = Vec6::Zero();
  double cost = 0.0;
  double sum_sq = 0.0;
  int inliers = 0;
  int residuals = 0;
};

LinearSystem build_system(const Correspondences& c, const std::optional<TiltPrior>& tilt, const SE3& T_W_L,
                          const RegistrationConfig& config) {
  LinearSystem sys;
  const auto add = [&](const auto& r, const auto& J) {
    const double s = r.squaredNorm();
    const Robust rho = robustify(s, config.loss, config.loss_scale_m);
    sys.H.noalias() += rho.weight * J.transpose() * J;
    sys.g.noalias() += rho.weight * J.transpose() * r;
    sys.cost += rho.cost;
    sys.sum_sq += s;
    sys.inliers += s <= config.loss_scale_m * config.loss_scale_m;
    ++sys.residuals;
  };
  Jacobian3x6 J3;
  for (const EdgeCorrespondence& e : c.edges) add(edge_residual(T_W_L, e, &J3), J3);
  Jacobian1x6 J1;
  for (const PlaneCorrespondence& p : c.planes) {
    const Eigen::Matrix<double, 1, 1> r(plane_residual(T_W_L, p, &J1));
    add(r, J1);
  }
  if (tilt) {
    const Vec3 r = tilt_residual(T_W_L, tilt->up_L, &J3);
    sys.H.noalias() += tilt->weight * J3.transpose() * J3;
    sys.g.noalias() += tilt->weight * J3.transpose() * r;
    sys.cost += tilt->weight * r.squaredNorm();
  }
  return sys;
}

double degeneracy_threshold(const LinearSystem& sys, const RegistrationConfig& config) {
  return config.degenerate_min_eigenvalue_per_match * sys.residuals;
}

double cost_at(const Correspondences& c, const std::optional<TiltPrior>& tilt, const SE3& T_W_L,
               const RegistrationConfig& config) {
  double cost = tilt ? tilt->weight * tilt_residual(T_W_L, tilt->up_L).squaredNorm() : 0.0;
  for (const EdgeCorrespondence& e : c.edges) {
    cost += robustify(edge_residual(T_W_L, e).squaredNorm(), config.loss, config.loss_scale_m).cost;
  }
  for (const PlaneCorrespondence& p : c.planes) {
    const double r = plane_residual(T_W_L, p);
    cost += robustify(r * r, config.loss, config.loss_scale_m).cost;
  }
  return cost;
}

bool is_small(const Vec6& delta, const RegistrationConfig& config) {
  return delta.head<3>().norm() < config.converged_translation_m &&
         delta.tail<3>().norm() < config.converged_rotation_rad;
}

// Levenberg-Marquardt on fixed correspondences, until a step is small or none lowers the cost.
void levenberg_marquardt(const Correspondences& c, const std::optional<TiltPrior>& tilt, SE3& T_W_L, const Mat6& remap,
                         const RegistrationConfig& config) {
  double lambda = 1e-4;
  for (int it = 0; it < config.max_inner_iterations; ++it) {
    const LinearSystem sys = build_system(c, tilt, T_W_L, config);
    bool accepted = false;
    Vec6 step = Vec6::Zero();
    for (int attempt = 0; attempt < 8 && !accepted; ++attempt) {
      Mat6 damped = sys.H;
      damped.diagonal() += lambda * sys.H.diagonal().cwiseMax(1e-9);
      // Zhang et al. 2016 solution remapping: the update moves only along well-conditioned directions.
      step = remap * damped.ldlt().solve(-sys.g);
      const SE3 candidate = T_W_L * SE3::exp(step);
      if (cost_at(c, tilt, candidate, config) < sys.cost) {
        T_W_L = candidate;
        lambda = std::max(lambda / 10.0, 1e-7);
        accepted = true;
      } else {
        lambda *= 10.0;
      }
    }
    if (!accepted || is_small(step, config)) break;
  }
}

std::vector<FeaturePoint> downsampled(const std::vector<FeaturePoint>& points, double leaf_m) {
  if (leaf_m <= 0.0) return points;
  std::vector<Vec3> p;
  p.reserve(points.size());
  for (const FeaturePoint& f : points) p.push_back(f.p_L);
  std::vector<FeaturePoint> kept;
  for (const std::size_t i : voxel_downsample_indices(p, leaf_m)) kept.push_back(points[i]);
  return kept;
}

}  // namespace

RegistrationResult register_scan(const FeatureScan& features_L, const FeatureMap& map, const SE3& T_W_L_init,
                                 const RegistrationConfig& config, const std::optional<Vec3>& up_L_prior,
                                 double up_L_prior_sigma_rad) {
  const std::optional<TiltPrior> tilt = tilt_prior(up_L_prior, up_L_prior_sigma_rad, config);
  const std::vector<FeaturePoint> edges_L = downsampled(features_L.edges, config.source_edge_leaf_m);
  const std::vector<FeaturePoint> surfaces_L = downsampled(features_L.surfaces, config.source_surface_leaf_m);
  RegistrationResult result;
  result.T_W_L = T_W_L_init;
  result.num_edge_features = static_cast<int>(edges_L.size());
  result.num_surface_features = static_cast<int>(surfaces_L.size());
  Mat6 remap = Mat6::Identity();
  for (int outer = 0; outer < config.max_outer_iterations; ++outer) {
    const Correspondences c = associate(edges_L, surfaces_L, map, result.T_W_L, config.association);
    if (c.edges.size() + c.planes.size() < 6) break;
    if (outer == 0 && config.remap_degenerate_directions) {
      // Zhang et al. 2016 compute the degenerate directions once, at the initial guess. The tilt prior's
      // information counts: a tilt the map leaves free is then not frozen at the initial guess but follows the prior.
      const LinearSystem sys = build_system(c, tilt, result.T_W_L, config);
      remap = analyze_degeneracy(sys.H, degeneracy_threshold(sys, config)).well_conditioned_projection;
    }
    const SE3 before = result.T_W_L;
    levenberg_marquardt(c, tilt, result.T_W_L, remap, config);
    result.outer_iterations = outer + 1;
    // Converged when re-associating no longer moves the pose.
    if (is_small((before.inverse() * result.T_W_L).log(), config)) {
      result.converged = true;
      break;
    }
  }
  const Correspondences c = associate(edges_L, surfaces_L, map, result.T_W_L, config.association);
  const LinearSystem sys = build_system(c, tilt, result.T_W_L, config);
  const int matched = static_cast<int>(c.edges.size() + c.planes.size());
  result.num_edge_matches = static_cast<int>(c.edges.size());
  result.num_surface_matches = static_cast<int>(c.planes.size());
  const int total = result.num_edge_features + result.num_surface_features;
  result.matched_fraction = total > 0 ? double(matched) / total : 0.0;
  result.rms_residual_m = matched > 0 ? std::sqrt(sys.sum_sq / matched) : 0.0;
  result.inlier_fraction = matched > 0 ? double(sys.inliers) / matched : 0.0;
  result.degeneracy = analyze_degeneracy(sys.H, degeneracy_threshold(sys, config));
  return result;
}

}  // namespace vilslam::lidar
