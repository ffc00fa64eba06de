#pragma once
// Loop detection and loop constraints (paper, "Lidar enhanced loop closure"): each new key frame queries
// the BoW database of older key images (only those older than a time threshold), candidates are verified
// by descriptor matching against the left key image, a loop constraint is estimated by EPnP in RANSAC on
// the candidate's stereo-triangulated points and refined by ICP of the current key scan's sparse features
// against the candidate's key scan. A loop is accepted only when the
// ICP result is well constrained and agrees with EPnP and with the odometry (repeated structure guard).
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "common/lie.h"
#include "common/yaml_config.h"
#include "lidar/lidar_config.h"
#include "loop/bow_database.h"
#include "loop/descriptor_matching.h"
#include "loop/key_frame.h"
#include "loop/vocabulary.h"

namespace vilslam::loop {

struct LoopClosureConfig {
  bool enabled = true;
  KeyFramePolicy key_frames;
  // Detection.
  double min_time_gap_s = 30.0;        // paper's time threshold: candidates at least this much older
  int max_bow_candidates = 3;          // best BoW results verified per query
  double min_bow_score = 0.0;          // absolute floor of the BoW score
  DescriptorMatchConfig descriptor_matching;  // query's left key image vs candidate's (Hamming, ratio, mutual)
  int min_descriptor_matches = 20;     // of those, matches whose candidate row has a 3D point
  // EPnP in RANSAC on the candidate's 3D points and the query's left keypoints.
  int min_pnp_inliers = 15;
  double pnp_reprojection_px = 3.0;
  int pnp_ransac_iterations = 200;
  std::uint64_t pnp_ransac_seed = 1;   // cv::theRNG() state before each RANSAC
  // ICP of the query key scan against the candidate's (paper). The run's LiDAR registration settings, but
  // denser: LiDAR mapping thins an accumulated map, a single key scan keeps its features at this spacing and the
  // query's at this voxel leaf.
  double icp_map_point_spacing_m = 0.05;
  double icp_source_leaf_m = 0.1;
  // A single key scan is sparse across rings: planes need neighbours spread over two axes (second / largest
  // scatter eigenvalue, lidar::AssociationConfig::min_plane_spread_ratio), and the loss is tighter than
  // LiDAR mapping's. Measured in docs/loop.md ("ICP accuracy").
  double icp_min_plane_spread_ratio = 0.1;
  // Planes through the nearest neighbour (lidar::AssociationConfig::plane_through_nearest), 7 neighbours per fit:
  // a ring's points bulge off the chord of a curved wall, so the centroid's plane lies inside an arch; 10 leave a
  // corridor's return two weak directions (docs/loop.md, "Plane fits of single key scans").
  bool icp_plane_through_nearest = true;
  int icp_num_neighbors = 7;
  double icp_loss_scale_m = 0.05;
  double icp_min_matched_fraction = 0.25;  // query features that found a line or plane in the map
  double icp_min_inlier_fraction = 0.5;   // matched features within the loss scale of their line or plane
  double icp_max_rms_m = 0.3;             // over all matched features (non-overlapping parts included)
  double icp_min_eigenvalue_per_match = 0.01;  // degenerate below this (lidar/degeneracy.h), robust-weighted
  // Degenerate directions a loop may have: ICP keeps EPnP's value along them (solution remapping), so along a
  // corridor's axis the constraint is the visual one (paper: vision where LiDAR degenerates). 0: none.
  int icp_max_degenerate_directions = 1;
  // Beyond the paper: the constraint fuses EPnP and ICP by their information (constraint_fusion.h) instead of
  // keeping ICP's result; the sigmas scale EPnP's reprojection residuals and ICP's point-to-line/plane ones.
  bool fuse_epnp_icp = true;
  double epnp_sigma_px = 1.0;
  double icp_sigma_m = 0.05;
  // Consistency: EPnP vs ICP, and the loop vs the odometry's prediction of the same relative pose.
  double max_epnp_icp_translation_m = 0.3;
  double max_epnp_icp_rotation_rad = 0.0524;   // 3 degrees
  double max_odometry_disagreement_m = 2.0;    // plus the fraction below of the path between the two
  double max_odometry_disagreement_per_m = 0.05;
  // Loop factor noise for the global pose graph.
  double loop_sigma_m = 0.02;
  double loop_sigma_rad = 0.002;
  // Add the covariance of EPnP and ICP combined (their informations summed) to the sigmas above: a loop then
  // hardly constrains a direction neither measures well. false: the sigmas alone.
  bool loop_covariance_from_estimates = true;
  // Re-localization in a loaded map (run --load-map; docs/loop.md, "Map reuse"): this run joins the map's
  // frame once relocalization_loops map loops in a row, from different key frames, agree on where this run's
  // frame lies in the map (each loop's T_map_run within the agreement of the one before).
  int relocalization_loops = 2;
  double relocalization_agreement_m = 0.3;
  double relocalization_agreement_rad = 0.035;  // 2 degrees
  // Resuming after a reset (docs/loop.md, "Forced resets"): a resume candidate whose visual stages fail is verified
  // by ICP from the resume guess (LoopCloser::set_resume_guess), which stands in for EPnP with these sigmas, for
  // the first resume_window_s of the new segment. 0 s: never.
  double resume_window_s = 10.0;
  double resume_sigma_m = 0.1;
  double resume_sigma_rad = 0.02;
  // Degenerate ICP directions a resumed loop may have (the guess's value kept along them: a corridor's axis and
  // a tunnel's roll).
  int resume_max_degenerate_directions = 2;
  // The first sweep the mapper registers on the map after re-localizing (a reset or --load-map) joins the graph by
  // its predicted motion plus a loop from the nearest map key scan with the registration's information, instead of
  // by its registered motion, and that loop replaces the map loops verified from the resume guess
  // (pipeline/loop_closure_module.h; docs/loop.md, "Forced resets").
  bool join_registration = true;
};

// The `loop_closure:` section of a run config, bound to c's fields; validate after reading.
YamlFields loop_closure_yaml_fields(LoopClosureConfig& c);
// Throws InputError(source, ...) when a value is out of range.
void validate_loop_closure_config(const LoopClosureConfig& c, const std::string& source);

// One examined candidate: what each stage measured and the stage that rejected it ("" when accepted).
// Stages in order: "bow_score", "descriptor_matches", "pnp_inliers", "icp_fitness", "icp_degenerate",
// "epnp_icp_disagree", "odometry_disagree".
struct LoopCandidateRecord {
  std::size_t query_key_frame = 0;
  std::size_t candidate_key_frame = 0;
  std::size_t query_pose_index = 0;      // "to" of the loop factor (the current scan v)
  std::size_t candidate_pose_index = 0;  // "from" of the loop factor (the old key scan u)
  TimeNs query_t_ns = 0;                 // key scans' end times (their LiDAR pose times)
  TimeNs candidate_t_ns = 0;
  double bow_score = 0.0;
  int descriptor_matches = 0;
  int pnp_inliers = 0;
  double icp_rms_m = 0.0;
  double icp_matched_fraction = 0.0;
  double icp_inlier_fraction = 0.0;
  double icp_min_eigenvalue_per_match = 0.0;
  int icp_degenerate_directions = 0;  // eigenvalues per match below icp_min_eigenvalue_per_match
  double epnp_icp_translation_m = 0.0;
  double epnp_icp_rotation_rad = 0.0;
  double path_length_m = 0.0;            // odometry path between the two key frames (key frame poses)
  double odometry_disagreement_m = 0.0;
  SE3 T_Lu_Lv_epnp;                      // EPnP alone, moved into the key scans' frames
  SE3 T_Lu_Lv_icp;                       // ICP initialized at EPnP
  SE3 T_Lu_Lv;                           // the loop constraint (u = candidate, v = query): ICP, or fused with EPnP
  Mat6 information = Mat6::Identity();   // of T_Lu_Lv, [rho; phi]
  // A candidate of a loaded map: candidate_key_frame and candidate_pose_index index the map's key frames and
  // poses, candidate_t_ns is on the map's clock.
  bool map_candidate = false;
  // A resume candidate verified from the resume guess: its visual stages failed (descriptor_matches or pnp_inliers
  // below their bounds) and T_Lu_Lv_epnp holds the guess.
  bool resumed = false;
  std::string rejected_by;

  bool accepted() const { return rejected_by.empty(); }
  // Its images matched (descriptors and EPnP passed) but its geometry could not be trusted: rejected by the ICP's
  // fit, a degenerate ICP, EPnP and ICP disagreeing or the odometry contradicting it (issue 61: a loop that cannot be
  // trusted is rejected, and counted in the run's summary).
  bool rejected_as_untrusted() const {
    return !accepted() && rejected_by != "bow_score" && rejected_by != "descriptor_matches" && rejected_by != "pnp_inliers";
  }
};

class LoopCloser {
 public:
  // lidar: the run's LiDAR settings; the loop ICP uses its registration and feature map settings but for
  // icp_map_point_spacing_m, icp_source_leaf_m, icp_min_plane_spread_ratio, icp_plane_through_nearest,
  // icp_num_neighbors and icp_loss_scale_m. Throws InputError for an invalid config and std::invalid_argument
  // without a vocabulary.
  LoopCloser(const LoopClosureConfig& config, const lidar::LidarConfig& lidar,
             std::shared_ptr<const Vocabulary> vocabulary);

  // Verifies the BoW candidates of key_frame (its id is set here to the next position), then stores it in
  // the database and the key frame list, unless it revisits a stored key frame (KeyFramePolicy::keep_revisits):
  // then it is merged into that one, and its records name that one as the query key frame. T_W_L(pose_index) is the current best estimate of any earlier
  // graph pose (for the odometry check). Returns every examined candidate, in BoW order;
  // examination stops at the first accepted one (at most one loop per query). Throws InputError when the
  // key frame's image rows are inconsistent or it is not after the previous key frame.
  std::vector<LoopCandidateRecord> add_and_detect(KeyFrame key_frame,
                                                  const std::function<SE3(std::size_t)>& T_W_L_of_pose);

  // A saved map's key frames and poses (loop/map_file.h): from now on every key frame's candidates not
  // accepted among this run's own are looked for among them too, with no time threshold (another run). Until
  // set_in_map_frame(true) this run's poses are in a frame of their own, so the odometry check skips them.
  // resume_candidates: the map is this run's own before a reset, so the robot is near where it ends: its last
  // resume_candidates key frames are verified at every query too, after the BoW ones, whatever their rank (in a
  // corridor the BoW ranks places that look alike above the one the robot is at).
  // Throws std::invalid_argument when a key frame's pose index is outside the poses.
  void load_map(std::vector<KeyFrame> key_frames, Trajectory poses, std::size_t resume_candidates = 0);
  // This run's poses (T_W_L_of_pose) are now in the map's frame: its candidates get the odometry check, with
  // config.max_odometry_disagreement_m as the allowance.
  void set_in_map_frame(bool in_map_frame) { in_map_frame_ = in_map_frame; }
  // After a reset, where this run's frame is believed to lie in the map (T_map_run): the map's last pose carried
  // across the reset by the new segment's first motion (LoopClosureModule). Resume candidates that fail the visual
  // stages are then verified by ICP from it; std::nullopt stops that.
  void set_resume_guess(std::optional<SE3> T_map_run) { resume_T_map_run_ = std::move(T_map_run); }
  std::size_t resume_candidates() const { return resume_candidates_; }
  const std::vector<KeyFrame>& map_key_frames() const { return map_key_frames_; }
  const Trajectory& map_poses() const { return map_poses_; }

  const std::vector<KeyFrame>& key_frames() const { return key_frames_; }
  // Hands the key frames over (to a saved map) once no more will be added; the closer keeps none.
  std::vector<KeyFrame> release_key_frames() { return std::move(key_frames_); }
  const LoopClosureConfig& config() const { return config_; }

 private:
  // Where candidates come from: this run's key frames, or a loaded map's.
  struct CandidatePool {
    const std::vector<KeyFrame>& key_frames;
    std::function<SE3(std::size_t)> T_W_L_of_pose;  // of the pool's pose indices
    bool from_map = false;
  };
  // The relative pose the ICP starts from and its information.
  struct InitialEstimate {
    SE3 T_Lu_Lv;
    Mat6 information;
  };
  // Descriptor matching and EPnP of u's and v's key images (their scores go into r); none when a stage fails (its
  // name in r.rejected_by).
  std::optional<InitialEstimate> visual_estimate(const KeyFrame& u, const KeyFrame& v, LoopCandidateRecord& r) const;
  Mat6 resume_information() const;
  // Runs the stages on candidate u of query v and stops at the first that fails. T_W_Lv_of_pose: this run's poses.
  LoopCandidateRecord verify(const KeyFrame& u, const KeyFrame& v, double bow_score, const CandidatePool& pool,
                             const std::function<SE3(std::size_t)>& T_W_Lv_of_pose) const;
  // Verifies candidates in BoW order and appends their records; true when one was accepted (the last record).
  bool verify_candidates(const std::vector<LoopCandidate>& candidates, const KeyFrame& v, const CandidatePool& pool,
                         const std::function<SE3(std::size_t)>& T_W_Lv_of_pose,
                         std::vector<LoopCandidateRecord>& records) const;

  LoopClosureConfig config_;
  lidar::LidarConfig lidar_;
  std::shared_ptr<const Vocabulary> vocabulary_;
  BowDatabase database_;
  std::vector<KeyFrame> key_frames_;
  BowDatabase map_database_;
  std::vector<KeyFrame> map_key_frames_;
  std::size_t resume_candidates_ = 0;
  std::optional<SE3> resume_T_map_run_;
  Trajectory map_poses_;
  bool in_map_frame_ = false;
};

}  // namespace vilslam::loop
