#pragma once
// Scan-to-map registration (paper Sec. "Scan to map registration", after LOAM): the dewarped feature points
// are matched to lines and planes of the map and the LiDAR pose is refined by Levenberg-Marquardt on the
// robustified point-to-line and point-to-plane distances, re-associating between outer iterations.
#include <optional>

#include "lidar/correspondences.h"
#include "lidar/degeneracy.h"
#include "lidar/feature_map.h"

namespace vilslam::lidar {

enum class RobustLoss { kHuber, kCauchy };

struct RegistrationConfig {
  AssociationConfig association;
  int max_outer_iterations = 10;  // each re-associates correspondences
  int max_inner_iterations = 4;   // LM steps per association
  // Pose change below which an iteration has converged (LOAM uses 0.05 cm and 0.05 deg).
  double converged_translation_m = 5e-4;
  double converged_rotation_rad = 8.7e-4;
  RobustLoss loss = RobustLoss::kCauchy;
  double loss_scale_m = 0.1;
  double source_edge_leaf_m = 0.2;     // the scan's features are voxel-downsampled before matching
  double source_surface_leaf_m = 0.4;
  // Zhang et al. 2016 threshold on the eigenvalues of J^T J, taken per matched feature so that it does not
  // depend on how many features the scan has.
  double degenerate_min_eigenvalue_per_match = 0.01;
  bool remap_degenerate_directions = false;  // keep the initial (prior) motion along degenerate directions
  // Tilt prior (beyond the paper, as LIO systems use the IMU): the LiDAR's roll and pitch are pulled towards a
  // gravity-referenced prior's (the VIO's) with this sigma (0.3 deg, the order of the VIO's tilt error; chosen on
  // the tuning seeds, docs/lidar.md); weight (loss_scale_m / sigma)^2 against the point residuals. Used only
  // when register_scan is given the prior's up direction; 0 = off.
  double tilt_prior_sigma_rad = 0.00524;
};

struct RegistrationResult {
  SE3 T_W_L;
  bool converged = false;
  int outer_iterations = 0;
  int num_edge_matches = 0;
  int num_surface_matches = 0;
  int num_edge_features = 0;
  int num_surface_features = 0;
  double matched_fraction = 0.0;   // source features that found a line or plane
  double rms_residual_m = 0.0;     // over matched features, at the solution
  double inlier_fraction = 0.0;    // matched features within loss_scale_m of their line or plane
  Degeneracy degeneracy;           // of the information matrix at the solution
};

// Registers dewarped features (LiDAR frame at the scan end) to the map, starting from T_W_L_init.
// up_L_prior: the world's up e_z in the LiDAR frame at the scan end from a gravity-referenced motion prior
// (R_W_L_prior^T e_z); with config.tilt_prior_sigma_rad > 0 it adds the tilt prior, whose information also
// enters the degeneracy analysis (so a tilt the map does not constrain follows the prior, not the initial guess).
// up_L_prior_sigma_rad: the prior's own tilt standard deviation when known (the VIO's covariance); the tilt
// prior's sigma is the larger of it and config.tilt_prior_sigma_rad.
RegistrationResult register_scan(const FeatureScan& features_L, const FeatureMap& map, const SE3& T_W_L_init,
                                 const RegistrationConfig& config,
                                 const std::optional<Vec3>& up_L_prior = std::nullopt, double up_L_prior_sigma_rad = 0.0);

}  // namespace vilslam::lidar
