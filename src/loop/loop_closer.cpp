#include "loop/loop_closer.h"

#include <algorithm>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>

#include "common/error.h"
#include "frontend/outlier_rejection.h"
#include "lidar/registration.h"
#include "loop/constraint_fusion.h"
#include "loop/loop_constraint.h"
#include "loop/pose_graph.h"

namespace vilslam::loop {
namespace {

void check_key_frame(const KeyFrame& k, TimeNs last_t_ns, bool has_last) {
  const std::string source = "loop key frame t_ns=" + std::to_string(k.image.t_ns);
  const cv::Mat& d = k.image.descriptors;
  if (!d.empty() && (d.type() != CV_8UC1 || d.cols != 32)) throw InputError(source, "descriptors are not N x 32 CV_8U");
  const std::size_t n = static_cast<std::size_t>(d.rows);
  if (k.image.left_norm.size() != n || k.image.points_C0.size() != n) {
    throw InputError(source, "left_norm and points_C0 need one entry per descriptor row");
  }
  if (has_last && k.image.t_ns <= last_t_ns) throw InputError(source, "not after the previous key frame");
}

LoopCandidateRecord rejected(LoopCandidateRecord r, const char* stage) {
  r.rejected_by = stage;
  return r;
}

}  // namespace

LoopCloser::LoopCloser(const LoopClosureConfig& config, const lidar::LidarConfig& lidar,
                       std::shared_ptr<const Vocabulary> vocabulary)
    : config_(config), lidar_(lidar), vocabulary_(std::move(vocabulary)) {
  validate_loop_closure_config(config_, "loop closure config");
  validate_lidar_config(lidar_, "loop closure lidar config");
  lidar_.map.edges.min_point_spacing_m = lidar_.map.surfaces.min_point_spacing_m = config_.icp_map_point_spacing_m;
  lidar_.registration.source_edge_leaf_m = lidar_.registration.source_surface_leaf_m = config_.icp_source_leaf_m;
  lidar_.registration.association.min_plane_spread_ratio = config_.icp_min_plane_spread_ratio;
  lidar_.registration.association.plane_through_nearest = config_.icp_plane_through_nearest;
  lidar_.registration.association.num_neighbors = config_.icp_num_neighbors;
  lidar_.registration.loss_scale_m = config_.icp_loss_scale_m;
  if (!vocabulary_ || vocabulary_->empty()) throw std::invalid_argument("LoopCloser needs a trained vocabulary");
}

void LoopCloser::load_map(std::vector<KeyFrame> key_frames, Trajectory poses, std::size_t resume_candidates) {
  for (std::size_t i = 0; i < key_frames.size(); ++i) {
    if (key_frames[i].pose_index >= poses.size()) {
      throw std::invalid_argument("loop closer: map key frame " + std::to_string(i) + " has no pose");
    }
    key_frames[i].id = i;
    map_database_.add(static_cast<std::int64_t>(i), key_frames[i].image.t_ns, key_frames[i].image.bow);
  }
  map_key_frames_ = std::move(key_frames);
  map_poses_ = std::move(poses);
  resume_candidates_ = std::min(resume_candidates, map_key_frames_.size());
}

bool LoopCloser::verify_candidates(const std::vector<LoopCandidate>& candidates, const KeyFrame& v,
                                   const CandidatePool& pool, const std::function<SE3(std::size_t)>& T_W_Lv_of_pose,
                                   std::vector<LoopCandidateRecord>& records) const {
  for (const LoopCandidate& c : candidates) {
    records.push_back(verify(pool.key_frames[static_cast<std::size_t>(c.id)], v, c.score, pool, T_W_Lv_of_pose));
    if (records.back().accepted()) return true;
  }
  return false;
}

std::vector<LoopCandidateRecord> LoopCloser::add_and_detect(KeyFrame key_frame,
                                                            const std::function<SE3(std::size_t)>& T_W_L_of_pose) {
  check_key_frame(key_frame, key_frames_.empty() ? 0 : key_frames_.back().image.t_ns, !key_frames_.empty());
  key_frame.id = key_frames_.size();
  const KeyFrame& v = key_frame;
  const auto max_candidates = static_cast<std::size_t>(config_.max_bow_candidates);
  std::vector<LoopCandidateRecord> records;
  // Loop detection: the BoW database of key images older than the time threshold (paper, "Loop detection"),
  // at most one loop per query: the first accepted in BoW order.
  const std::vector<LoopCandidate> candidates =
      database_.query(v.image.bow, v.image.t_ns, max_candidates, s_to_ns(config_.min_time_gap_s));
  const bool accepted = verify_candidates(candidates, v, {key_frames_, T_W_L_of_pose, false}, T_W_L_of_pose, records);
  if (accepted && !config_.key_frames.keep_revisits) {
    const LoopCandidateRecord& loop = records.back();
    const PoseDifference d = pose_difference(loop.T_Lu_Lv, SE3());
    if (d.translation_m < config_.key_frames.min_translation_m && d.rotation_rad < config_.key_frames.min_rotation_rad) {
      for (LoopCandidateRecord& r : records) r.query_key_frame = loop.candidate_key_frame;
      return records;
    }
  }
  if (!accepted && !map_key_frames_.empty()) {
    // A loaded map's key images: all of them, whatever their time (another run's clock).
    std::vector<LoopCandidate> in_map =
        map_database_.query(v.image.bow, std::numeric_limits<TimeNs>::max(), max_candidates, 0);
    for (std::size_t id = map_key_frames_.size() - resume_candidates_; id < map_key_frames_.size(); ++id) {
      const bool listed = std::any_of(in_map.begin(), in_map.end(),
                                      [id](const LoopCandidate& c) { return c.id == static_cast<std::int64_t>(id); });
      if (!listed) {
        in_map.push_back({static_cast<std::int64_t>(id), map_key_frames_[id].image.t_ns,
                          bow_score(v.image.bow, map_key_frames_[id].image.bow)});
      }
    }
    const auto T_W_L_of_map_pose = [this](std::size_t i) { return map_poses_.at(i).T_W_B; };
    verify_candidates(in_map, v, {map_key_frames_, T_W_L_of_map_pose, true}, T_W_L_of_pose, records);
  }
  database_.add(static_cast<std::int64_t>(key_frame.id), key_frame.image.t_ns, key_frame.image.bow);
  key_frames_.push_back(std::move(key_frame));
  return records;
}

std::optional<LoopCloser::InitialEstimate> LoopCloser::visual_estimate(const KeyFrame& u, const KeyFrame& v,
                                                                       LoopCandidateRecord& r) const {
  // Descriptor matching of the left key images (paper, "Loop detection"), against candidate rows with a 3D point.
  std::vector<int> rows_with_point;
  for (int i = 0; i < u.image.descriptors.rows; ++i) {
    if (u.image.points_C0[i].allFinite()) rows_with_point.push_back(i);
  }
  cv::Mat train(static_cast<int>(rows_with_point.size()), 32, CV_8U);
  for (std::size_t k = 0; k < rows_with_point.size(); ++k) {
    u.image.descriptors.row(rows_with_point[k]).copyTo(train.row(static_cast<int>(k)));
  }
  const std::vector<DescriptorMatch> matches =
      match_descriptors(v.image.descriptors, train, config_.descriptor_matching);
  r.descriptor_matches = static_cast<int>(matches.size());
  if (r.descriptor_matches < config_.min_descriptor_matches) {
    r.rejected_by = "descriptor_matches";
    return std::nullopt;
  }

  // Visual loop constraint by EPnP on the candidate's triangulated points (paper, "Loop constraint").
  std::vector<Vec3> p_C0u;
  std::vector<Eigen::Vector2d> xy_C0v;
  for (const DescriptorMatch& m : matches) {
    p_C0u.push_back(u.image.points_C0[rows_with_point[m.train]]);
    xy_C0v.push_back(v.image.left_norm[m.query]);
  }
  FrontendConfig pnp_config;
  pnp_config.pnp_min_points = 5;  // OpenCV's EPnP RANSAC sample; the stage's own bound is min_pnp_inliers
  pnp_config.pnp_ransac_iterations = config_.pnp_ransac_iterations;
  pnp_config.pnp_ransac_threshold_px = config_.pnp_reprojection_px;
  pnp_config.ransac_seed = config_.pnp_ransac_seed;
  const MotionEstimate pnp = estimate_motion_pnp(p_C0u, xy_C0v, v.image.focal_px, pnp_config, PnpSolver::kEPnP);
  r.pnp_inliers = pnp.inliers;
  if (!pnp.valid || r.pnp_inliers < config_.min_pnp_inliers) {
    r.rejected_by = "pnp_inliers";
    return std::nullopt;
  }
  // EPnP's information, from its reprojection Jacobians, moved into the key scans' frames.
  const Mat6 information = information_in_lidar_frames(
      pnp_information(pnp.T_C0cur_C0prev, p_C0u, xy_C0v, v.image.focal_px, config_.pnp_reprojection_px,
                      config_.epnp_sigma_px),
      pnp.T_C0cur_C0prev, v.T_L_C0);
  return InitialEstimate{lidar_constraint_from_camera(pnp.T_C0cur_C0prev, u.T_L_C0, v.T_L_C0),  // cur = v, prev = u
                         information};

}

Mat6 LoopCloser::resume_information() const {
  return information_from_sigmas(config_.resume_sigma_m, config_.resume_sigma_rad);
}

LoopCandidateRecord LoopCloser::verify(const KeyFrame& u, const KeyFrame& v, double bow_score,
                                       const CandidatePool& pool,
                                       const std::function<SE3(std::size_t)>& T_W_Lv_of_pose) const {
  LoopCandidateRecord r;
  r.map_candidate = pool.from_map;
  r.query_key_frame = v.id;
  r.candidate_key_frame = u.id;
  r.query_pose_index = v.pose_index;
  r.candidate_pose_index = u.pose_index;
  r.query_t_ns = v.scan_t_ns;
  r.candidate_t_ns = u.scan_t_ns;
  r.bow_score = bow_score;
  if (bow_score < config_.min_bow_score) return rejected(std::move(r), "bow_score");

  // The visual estimate: descriptor matching and EPnP (paper); for a resume candidate that fails them, the resume
  // guess instead, when there is one (set_resume_guess).
  std::optional<InitialEstimate> initial = visual_estimate(u, v, r);
  if (!initial) {
    const bool resume_candidate = pool.from_map && u.id + resume_candidates_ >= map_key_frames_.size();
    if (!resume_candidate || !resume_T_map_run_) return r;
    initial = InitialEstimate{pool.T_W_L_of_pose(u.pose_index).inverse() * *resume_T_map_run_ * T_W_Lv_of_pose(v.pose_index),
                              resume_information()};
    r.resumed = true;
    r.rejected_by.clear();
  }
  r.T_Lu_Lv_epnp = initial->T_Lu_Lv;

  // Refinement by ICP of the sparse LiDAR features against the candidate's key scan in Lu, initialized at the
  // visual constraint (or the resume guess).
  lidar::FeatureMap map(lidar_.map);
  map.insert(u.features_L, SE3());
  const lidar::RegistrationResult icp = lidar::register_scan(v.features_L, map, r.T_Lu_Lv_epnp, lidar_.registration);
  r.T_Lu_Lv_icp = r.T_Lu_Lv = icp.T_W_L;
  r.icp_rms_m = icp.rms_residual_m;
  r.icp_matched_fraction = icp.matched_fraction;
  r.icp_inlier_fraction = icp.inlier_fraction;
  const int icp_matches = icp.num_edge_matches + icp.num_surface_matches;
  r.icp_min_eigenvalue_per_match = icp_matches > 0 ? icp.degeneracy.eigenvalues(0) / icp_matches : 0.0;
  for (int i = 0; i < 6; ++i) {
    const double per_match = icp_matches > 0 ? icp.degeneracy.eigenvalues(i) / icp_matches : 0.0;
    r.icp_degenerate_directions += per_match < config_.icp_min_eigenvalue_per_match;
  }
  const PoseDifference epnp_icp = pose_difference(r.T_Lu_Lv_epnp, r.T_Lu_Lv_icp);
  r.epnp_icp_translation_m = epnp_icp.translation_m;
  r.epnp_icp_rotation_rad = epnp_icp.rotation_rad;
  // Repeated-structure guard: the loop against the odometry's T_Lu_Lv, allowing drift along the path. A map
  // candidate has no path to this run: the allowance is the constant part, and before this run is in the
  // map's frame there is nothing to compare with.
  const SE3 T_W_Lu = pool.T_W_L_of_pose(u.pose_index), T_W_Lv = T_W_Lv_of_pose(v.pose_index);
  const bool odometry_check = !pool.from_map || in_map_frame_;
  if (!pool.from_map) {
    Vec3 p_prev_W = T_W_Lu.translation();
    for (std::size_t j = u.id + 1; j < key_frames_.size(); ++j) {
      const Vec3 p_W = T_W_Lv_of_pose(key_frames_[j].pose_index).translation();
      r.path_length_m += (p_W - p_prev_W).norm();
      p_prev_W = p_W;
    }
    r.path_length_m += (T_W_Lv.translation() - p_prev_W).norm();
  }
  if (odometry_check) r.odometry_disagreement_m = pose_difference(T_W_Lu.inverse() * T_W_Lv, r.T_Lu_Lv).translation_m;

  if (r.icp_matched_fraction < config_.icp_min_matched_fraction ||
      r.icp_inlier_fraction < config_.icp_min_inlier_fraction || r.icp_rms_m > config_.icp_max_rms_m) {
    return rejected(std::move(r), "icp_fitness");
  }
  const int max_degenerate = r.resumed ? config_.resume_max_degenerate_directions : config_.icp_max_degenerate_directions;
  if (r.icp_degenerate_directions > max_degenerate) {
    return rejected(std::move(r), "icp_degenerate");
  }
  if (r.epnp_icp_translation_m > config_.max_epnp_icp_translation_m ||
      r.epnp_icp_rotation_rad > config_.max_epnp_icp_rotation_rad) {
    return rejected(std::move(r), "epnp_icp_disagree");
  }
  if (odometry_check && r.odometry_disagreement_m > config_.max_odometry_disagreement_m +
                                                        config_.max_odometry_disagreement_per_m * r.path_length_m) {
    return rejected(std::move(r), "odometry_disagree");
  }
  const Mat6& epnp_information = initial->information;
  // Along a degenerate direction the remapping kept EPnP's value: ICP measured nothing there.
  Vec6 icp_eigenvalues = icp.degeneracy.eigenvalues;
  for (int i = 0; i < 6; ++i) {
    if (icp_matches == 0 || icp_eigenvalues(i) / icp_matches < config_.icp_min_eigenvalue_per_match) {
      icp_eigenvalues(i) = 0.0;
    }
  }
  const Mat6& V = icp.degeneracy.eigenvectors;
  const Mat6 icp_information =
      V * icp_eigenvalues.asDiagonal() * V.transpose() / (config_.icp_sigma_m * config_.icp_sigma_m);
  if (config_.fuse_epnp_icp) {
    r.T_Lu_Lv = fuse_estimates(r.T_Lu_Lv_epnp, epnp_information, r.T_Lu_Lv_icp, icp_information);
  }
  // Loop factor noise: the config sigmas (docs/loop.md: why not ICP's J^T J alone) plus, where neither estimate
  // measures a direction well (outdoors, the axis along which ICP kept a distant-point EPnP), the combined
  // estimate's own covariance.
  const Mat6 floor_information = information_from_sigmas(config_.loop_sigma_m, config_.loop_sigma_rad);
  r.information = config_.loop_covariance_from_estimates
                      ? information_with_floor(epnp_information + icp_information, floor_information)
                      : floor_information;
  return r;
}

}  // namespace vilslam::loop
