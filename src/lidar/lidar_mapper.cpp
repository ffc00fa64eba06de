#include "lidar/lidar_mapper.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>

#include "common/error.h"
#include "common/log.h"
#include "lidar/dewarp.h"
#include "lidar/registration.h"

namespace vilslam::lidar {

namespace {

// Constant-velocity motion: the pose at t relative to the pose at end_t_ns, Exp(((t - t_end) / dt) xi).
PoseAtTime constant_velocity(const Vec6& motion, TimeNs duration_ns, TimeNs end_t_ns) {
  return [motion, duration_ns, end_t_ns](TimeNs t_ns) {
    return SE3::exp(motion * (double(t_ns - end_t_ns) / double(duration_ns)));
  };
}

// More of the sweep's features within the loss scale of a line or plane; on a tie, the smaller rms residual.
bool fits_better(const RegistrationResult& a, const RegistrationResult& b) {
  const double inliers_a = a.matched_fraction * a.inlier_fraction, inliers_b = b.matched_fraction * b.inlier_fraction;
  if (inliers_a != inliers_b) return inliers_a > inliers_b;
  return a.rms_residual_m < b.rms_residual_m;
}

double elapsed_ms(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

// The mapper remaps degenerate directions; 0.03 per match flags the simulated tunnel (its along-axis
// eigenvalue is not zero, from noisy plane fits) and not the highbay (docs/lidar.md).
LidarMapperConfig::LidarMapperConfig() {
  lidar.registration.remap_degenerate_directions = true;
  lidar.registration.degenerate_min_eigenvalue_per_match = 0.03;
}

YamlFields lidar_mapper_yaml_fields(LidarMapperConfig& c) {
  YamlFields fields = lidar_yaml_fields(c.lidar);
  fields.push_back(yaml_section(
      "mapper", {yaml_value("dewarp", c.dewarp), yaml_value("lidar_only_redewarp", c.lidar_only_redewarp)}));
  fields.push_back(yaml_section(
      "loss", {yaml_value("enabled", c.loss.enabled), yaml_value("min_matched_fraction", c.loss.min_matched_fraction),
               yaml_value("min_inlier_fraction", c.loss.min_inlier_fraction), yaml_value("gap_s", c.loss.gap_s),
               yaml_value("max_correction_m", c.loss.max_correction_m),
               yaml_value("max_correction_deg", c.loss.max_correction_deg),
               yaml_value("lost_after_rejected", c.loss.lost_after_rejected)}));
  return fields;
}

LidarMapper::LidarMapper(const LidarMapperConfig& config, const SE3& T_I_L, TimeNs sweep_period_ns, bool spinning)
    : config_(config), T_I_L_(T_I_L), sweep_period_ns_(sweep_period_ns), spinning_(spinning), map_(config.lidar.map) {}

std::string LidarMapper::azimuth_times() const {
  switch (azimuth_clock_.state()) {
    case AzimuthClockVote::State::kTimed: return "yes";
    case AzimuthClockVote::State::kInstant: return "no";
    case AzimuthClockVote::State::kUndecided: break;
  }
  return "undecided";
}

RegistrationConfig LidarMapper::registration_without_prior() const {
  constexpr double kMaxIterationFactor = 5.0;
  RegistrationConfig c = config_.lidar.registration;
  const double widened = std::max(1.0, model_deviation_.sigma_m() / c.loss_scale_m);
  c.loss_scale_m *= widened;
  c.max_outer_iterations = static_cast<int>(std::ceil(c.max_outer_iterations * std::min(widened, kMaxIterationFactor)));
  return c;
}

void LidarMapper::vote_azimuth_clock(const LidarScan& scan, const std::vector<Vec3>& points_L,
                                     const LidarMappingResult& instant) {
  const TimeNs end_t_ns = instant.t_ns;
  const SE3 motion = previous_->T_W_L.inverse() * instant.T_W_L;
  if (rms_displacement_m(points_L, motion) < ModelDeviation::kMinMotion_m) return;  // at rest both fit alike
  LidarScan timed = scan;
  assign_azimuth_times(timed, ns_to_s(sweep_period_ns_));
  const TimeNs timed_end_ns = timed.end_t_ns(), duration_ns = end_t_ns - previous_->end_t_ns;
  const Vec6 xi = motion.log();
  const FeatureScan raw = extract_features(timed, config_.lidar.rings, features_for_registration(config_.lidar));
  const FeatureScan features = dewarp(raw, timed_end_ns, constant_velocity(xi, duration_ns, timed_end_ns));
  const SE3 T_W_L_timed = instant.T_W_L * SE3::exp(xi * (double(timed_end_ns - end_t_ns) / double(duration_ns)));
  const RegistrationResult r = register_scan(features, map_, T_W_L_timed, registration_without_prior());
  azimuth_clock_.vote(r.rms_residual_m, instant.rms_residual_m);
  if (azimuth_clock_.state() == AzimuthClockVote::State::kTimed) {
    spdlog::info("LiDAR sweeps without point times: their azimuths give the times (they fit the map better so)");
  } else if (azimuth_clock_.state() == AzimuthClockVote::State::kInstant) {
    spdlog::info("LiDAR sweeps without point times: each taken as one instant (they fit the map worse with azimuth "
                 "times: deskewed already)");
  }
}

SE3 LidarMapper::motion_since_previous(TimeNs end_t_ns, const std::optional<SE3>& T_W_L_prior_end) const {
  if (T_W_L_prior_end && previous_->T_W_L_prior) return previous_->T_W_L_prior->inverse() * *T_W_L_prior_end;
  if (!previous_->motion) return SE3();
  const double ratio = double(end_t_ns - previous_->end_t_ns) / double(previous_->motion_duration_ns);
  return SE3::exp(*previous_->motion * ratio);
}

RegistrationResult LidarMapper::reregister_lidar_only(const FeatureScan& raw, TimeNs end_t_ns, const SE3& T_W_L,
                                                      FeatureScan& features, const RegistrationConfig& config) {
  // The registered motion of this sweep replaces the extrapolated one for dewarping (the role of LOAM's
  // scan-to-scan odometry), and the sweep is registered again from that solution.
  const Vec6 motion = (previous_->T_W_L.inverse() * T_W_L).log();
  const TimeNs duration_ns = end_t_ns - previous_->end_t_ns;
  features = dewarp(raw, end_t_ns, constant_velocity(motion, duration_ns, end_t_ns));
  if (first_raw_) {
    // The first sweep went into the map undewarped (no motion was known): rebuild it dewarped.
    map_ = FeatureMap(config_.lidar.map);
    const TimeNs first_end_ns = previous_->end_t_ns;
    map_.insert(dewarp(*first_raw_, first_end_ns, constant_velocity(motion, duration_ns, first_end_ns)),
                previous_->T_W_L);
    first_raw_.reset();
  }
  return register_scan(features, map_, T_W_L, config);
}

void LidarMapper::reanchor() {
  map_ = FeatureMap(config_.lidar.map);
  reanchored_ = previous_.has_value();
}

void LidarMapper::relocalize(const SE3& T_W_L_last, const std::vector<PosedFeatureScan>& scans) {
  if (!previous_) throw std::logic_error("LidarMapper::relocalize before the first sweep");
  // The prior-aided poses move with the last one, so that their mean motion stays a motion.
  const SE3 T_corrected_W = T_W_L_last * previous_->T_W_L.inverse();
  for (auto& [t_ns, T_W_L] : aided_poses_) T_W_L = T_corrected_W * T_W_L;
  previous_->T_W_L = T_W_L_last;
  map_ = build_feature_map(config_.lidar.map, scans, T_W_L_last.translation());
}

LidarMappingResult LidarMapper::process(const LidarScan& sweep, const std::function<SE3(TimeNs)>& T_W_I_prior,
                                        const std::function<SE3(TimeNs)>& T_O_I_dewarp, double prior_tilt_sigma_rad) {
  const auto start = std::chrono::steady_clock::now();
  if (sweep.points.empty()) throw InputError("lidar scan", "empty scan at t_ns " + std::to_string(sweep.t_ns));
  // A spinning sweep without per-point times: one instant at its stamp until the azimuth clock is voted in.
  const bool clock_open = spinning_ && config_.dewarp && sweep_period_ns_ > 0 && !has_point_times(sweep);
  std::optional<LidarScan> timed;
  if (clock_open && azimuth_clock_.state() == AzimuthClockVote::State::kTimed) {
    timed = sweep;
    assign_azimuth_times(*timed, ns_to_s(sweep_period_ns_));
  }
  const LidarScan& scan = timed ? *timed : sweep;
  const TimeNs end_t_ns = scan.end_t_ns();
  if (previous_ && end_t_ns <= previous_->end_t_ns) {
    throw InputError("lidar scan", "scan ending at " + std::to_string(end_t_ns) + " ns is not after the previous one");
  }
  const bool has_prior = static_cast<bool>(T_W_I_prior);
  const bool lidar_only_refine = !has_prior && config_.dewarp && config_.lidar_only_redewarp;
  const auto prior_T_W_L = [&](TimeNs t_ns) { return T_W_I_prior(t_ns) * T_I_L_; };

  // Features come from the raw sweep, before dewarping (paper Sec. "Lidar mapping").
  const FeatureScan raw = extract_features(scan, config_.lidar.rings, features_for_registration(config_.lidar));
  FeatureScan features = raw;

  std::optional<SE3> T_W_L_prior_end;
  if (has_prior) {
    T_W_L_prior_end = prior_T_W_L(end_t_ns);
    if (!T_W_L_prior_end->matrix().allFinite()) {
      throw InputError("motion prior", "non-finite pose at t_ns " + std::to_string(end_t_ns));
    }
  }
  const bool constant_velocity_known = previous_ && previous_->motion.has_value();
  if (config_.dewarp && has_prior && T_O_I_dewarp) {
    features = dewarp(features, end_t_ns, [&](TimeNs t_ns) { return T_O_I_dewarp(t_ns) * T_I_L_; });
  } else if (config_.dewarp && has_prior) {
    features = dewarp(features, end_t_ns, prior_T_W_L);
  } else if (config_.dewarp && constant_velocity_known) {
    features = dewarp(features, end_t_ns,
                      constant_velocity(*previous_->motion, previous_->motion_duration_ns, end_t_ns));
  }

  LidarMappingResult out;
  out.t_ns = end_t_ns;
  // The prior's tilt (its up direction in L; VIO: referenced to gravity), for the registration's tilt prior.
  if (T_W_L_prior_end) {
    out.up_L_prior = T_W_L_prior_end->rotation().transpose() * Vec3::UnitZ();
    out.up_L_prior_sigma_rad = prior_tilt_sigma_rad;
  }
  if (!previous_) {
    // The first scan defines the map frame: the VIO world frame when a prior is given.
    out.T_W_L = T_W_L_prior_end.value_or(SE3());
    if (lidar_only_refine) first_raw_ = raw;
  } else if (reanchored_) {
    // A fresh map begins at the prediction: the last kept pose and the motion since (prior or constant velocity).
    out.T_prev_predicted = motion_since_previous(end_t_ns, T_W_L_prior_end);
    out.T_W_L = previous_->T_W_L * out.T_prev_predicted;
    out.reanchored = true;
  } else {
    // Paper: L*_{k+1} = L_k T_trans.
    const SE3 T_trans = motion_since_previous(end_t_ns, T_W_L_prior_end);
    const RegistrationConfig registration = has_prior ? config_.lidar.registration : registration_without_prior();
    RegistrationResult r = register_scan(features, map_, previous_->T_W_L * T_trans, registration, out.up_L_prior,
                                         out.up_L_prior_sigma_rad);
    if (!has_prior && (!r.converged || registration.loss_scale_m > config_.lidar.registration.loss_scale_m)) {
      // A turn the constant-velocity model carries on after it stopped (a hand-held sensor at 2 Hz turns 43 deg in
      // one sweep and 9 in the next): registered again from the last pose, the better fit is kept.
      RegistrationResult from_last = register_scan(features, map_, previous_->T_W_L, registration);
      if (fits_better(from_last, r)) r = std::move(from_last);
    }
    if (lidar_only_refine) r = reregister_lidar_only(raw, end_t_ns, r.T_W_L, features, registration);
    out.T_W_L = r.T_W_L;
    out.degenerate = r.degeneracy.degenerate();
    out.degenerate_directions = r.degeneracy.degenerate_directions;
    out.information_eigenvalues = r.degeneracy.eigenvalues;
    const Mat6& V = r.degeneracy.eigenvectors;
    out.information = V * r.degeneracy.eigenvalues.asDiagonal() * V.transpose();
    out.T_prev_predicted = T_trans;
    out.rms_residual_m = r.rms_residual_m;
    out.matched_fraction = r.matched_fraction;
    out.inlier_fraction = r.inlier_fraction;
    const TimeNs start_t_ns = end_t_ns > scan.t_ns ? scan.t_ns : end_t_ns - sweep_period_ns_;
    out.gap_s = std::max(0.0, ns_to_s(start_t_ns - previous_->end_t_ns));
    out.converged = r.converged;
    const SE3 correction = (previous_->T_W_L * T_trans).inverse() * out.T_W_L;  // the jump from the prediction
    out.correction_m = correction.translation().norm();
    out.correction_deg = so3::log(correction.rotation()).norm() * 180.0 / M_PI;
    out.loss = mapping_loss(
        {out.matched_fraction, out.inlier_fraction, out.gap_s, out.correction_m, out.correction_deg, has_prior},
        config_.loss);
  }
  out.vio_prior = has_prior;
  if (out.loss != MappingLoss::kNone) {
    out.time_ms = elapsed_ms(start);
    return out;
  }
  out.num_edge_features = static_cast<int>(features.edges.size());
  out.num_surface_features = static_cast<int>(features.surfaces.size());
  const bool vote = clock_open && azimuth_clock_.state() == AzimuthClockVote::State::kUndecided;
  if (previous_ && !out.reanchored && (!has_prior || vote)) {  // the points only where they are used
    std::vector<Vec3> points_L;
    for (const FeaturePoint& f : features.surfaces) points_L.push_back(f.p_L);
    for (const FeaturePoint& f : features.edges) points_L.push_back(f.p_L);
    if (!has_prior) {
      model_deviation_.add(points_L, (previous_->T_W_L * out.T_prev_predicted).inverse() * out.T_W_L,
                           previous_->T_W_L.inverse() * out.T_W_L);
    }
    if (vote) vote_azimuth_clock(sweep, points_L, out);  // before the sweep enters the map it is compared with
  }
  map_.insert(features, out.T_W_L);
  reanchored_ = false;
  last_features_ = std::move(features);

  Previous next;
  next.end_t_ns = end_t_ns;
  next.T_W_L = out.T_W_L;
  next.T_W_L_prior = T_W_L_prior_end;
  if (has_prior) {
    aided_poses_.emplace_back(end_t_ns, out.T_W_L);
    if (aided_poses_.size() > kAidedPoses) aided_poses_.pop_front();
  }
  if (!has_prior && aided_poses_.size() >= 2) {
    // A VIO outage (no prior after sweeps that had one): the constant-velocity model is the mean motion of the
    // last prior-aided sweeps, and stays so. Learnt from the LiDAR-only sweeps, a degenerate corridor passes each
    // registration's slip on to the next prediction, which its degenerate sweeps keep (docs/lidar.md, "VIO outages
    // in a corridor").
    next.motion = (aided_poses_.front().second.inverse() * aided_poses_.back().second).log();
    next.motion_duration_ns = aided_poses_.back().first - aided_poses_.front().first;
  } else if (previous_) {
    next.motion = (previous_->T_W_L.inverse() * out.T_W_L).log();
    next.motion_duration_ns = end_t_ns - previous_->end_t_ns;
  }
  previous_ = next;
  out.time_ms = elapsed_ms(start);
  return out;
}

}  // namespace vilslam::lidar
