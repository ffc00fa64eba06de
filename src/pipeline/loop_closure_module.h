#pragma once
// The loop closure module of the paper's diagram, wired into the offline pipeline: key scans are chosen
// among the mapped sweeps (loop/key_frame.h policy) and associated by timestamp with the nearest stereo
// pair (the key image); the loop closer detects loops and estimates EPnP + ICP constraints; the global pose
// graph holds every LiDAR pose; an accepted loop re-optimizes it and returns a map correction to LiDAR
// mapping (paper, "Re-localization"). In this synchronous offline mode the correction is applied before
// the next sweep, so the paper's buffer of sweeps waiting for the correction is always empty.
#include <cstddef>
#include <deque>
#include <memory>
#include <optional>
#include <vector>

#include "common/calibration.h"
#include "common/types.h"
#include "frontend/camera_model.h"
#include "frontend/frontend_config.h"
#include "lidar/feature_map.h"
#include "lidar/lidar_mapper.h"
#include "loop/global_pose_graph.h"
#include "loop/loop_closer.h"
#include "loop/map_file.h"

namespace vilslam {

struct LoopClosureOutput {
  Trajectory lidar_odometry;  // the mapper's own motion, composed: lidar.tum
  Trajectory lidar_global;    // each pose as published, with the corrections known then: lidar_global.tum
  Trajectory lidar_final;     // the final optimized graph: lidar_final.tum
  std::vector<loop::LoopCandidateRecord> candidates;  // every examined candidate, accepted or not
  std::size_t key_frames = 0;
  std::vector<loop::KeyFrame> key_frame_data;  // the key frames themselves, for a saved map (loop/map_file.h)
  std::vector<double> key_frame_ms;   // key image extraction per key frame
  std::vector<double> detection_ms;   // detection + constraints (LoopCloser::add_and_detect) per key frame
  std::vector<double> correction_ms;  // graph optimization + map rebuild per accepted loop
  std::vector<double> final_solve_ms;  // the final solve (GlobalPoseGraph::optimize_final) of a run with loops
  // With a loaded map (load_map): when this run joined the map's frame (re-localization; none: it never did,
  // and every output is in the run's own frame), where the run's frame lay in the map then, and the loops
  // to the map's key frames in the graph.
  std::optional<TimeNs> relocalized_t_ns;
  SE3 T_map_run;
  std::size_t map_loops = 0;
};

// What LiDAR mapping must do after a loop: resume from T_W_L_last on a map rebuilt from the key scans.
struct MapCorrection {
  SE3 T_W_L_last;
  std::vector<lidar::PosedFeatureScan> key_scans;  // point into the loop closer's key frames
};

class LoopClosureModule {
 public:
  // lidar: the run's LiDAR settings (the loop ICP's registration; the map radius of corrections).
  // imu_motion: the VIO's jump-free IMU-rate poses T_O_I (the motion between a key image and its key scan).
  // With loop closure disabled it only records the odometry (lidar_global = lidar_final = lidar_odometry).
  LoopClosureModule(const loop::LoopClosureConfig& config, const loop::GlobalPoseGraphConfig& graph_config,
                    std::shared_ptr<const Vocabulary> vocabulary, const RigCalibration& calib,
                    const FrontendConfig& frontend_config, const lidar::LidarConfig& lidar,
                    const Trajectory* imu_motion);

  // A saved map to re-localize in (docs/loop.md, "Map reuse"), before the first sweep: its key frames become
  // loop candidates of every key frame; once relocalization_loops map loops agree, the graph moves into the
  // map's frame, the map loops join it as factors from the fixed map poses, and LiDAR mapping resumes on a
  // map that holds the saved key scans around it. Until then every output is in the run's own frame.
  // resume: the map is this run's own before a reset (the robot is near where it ends; LoopCloser::load_map).
  // Throws std::invalid_argument with loop closure disabled or after the first sweep.
  void load_map(loop::SavedMap map, bool resume = false);
  bool relocalized() const { return out_.relocalized_t_ns.has_value(); }

  // A stereo pair, its time already on the IMU clock. Completes a key frame waiting for its key image.
  void stereo(const StereoFrame& frame);
  // A sweep the mapper has just registered (features_L as the mapper registered them). A key scan becomes a
  // key frame once its key image is there (now, or with a later stereo pair).
  void scan_mapped(const lidar::LidarMappingResult& mapped, const lidar::FeatureScan& features_L);
  // The correction LiDAR mapping must apply before its next sweep, once per accepted loop.
  std::optional<MapCorrection> take_correction();

  // Published so far: each mapped sweep's pose with the corrections known then, and the examined candidates.
  const Trajectory& lidar_global() const { return out_.lidar_global; }
  const std::vector<loop::LoopCandidateRecord>& candidates() const { return out_.candidates; }

  // Fills lidar_final and the counts.
  LoopClosureOutput finish();

 private:
  struct PendingKeyScan {
    TimeNs scan_t_ns = 0;
    std::size_t pose_index = 0;
    lidar::FeatureScan features_L;
  };

  const StereoFrame* key_image_for(TimeNs scan_t_ns) const;
  // Builds the key frame of the pending key scan with the stereo pair, detects loops, corrects the graph.
  void add_key_frame(const PendingKeyScan& scan, const StereoFrame& frame);
  MapCorrection correction_at(std::size_t pose_index) const;
  // An accepted loop to a map key frame: a factor once re-localized, else a vote for where this run's frame
  // lies in the map, which re-localizes when enough in a row agree. True when the graph has a new map loop.
  bool add_map_loop(const loop::LoopCandidateRecord& r);
  // After a reset, within resume_window_s of the new segment's first pose: where its frame lies in the map if
  // the map's last pose is carried across the reset by the segment's first motion (LoopCloser::set_resume_guess).
  std::optional<SE3> resume_guess(TimeNs query_t_ns) const;

  loop::LoopClosureConfig config_;
  std::shared_ptr<const Vocabulary> vocabulary_;
  RigCalibration calib_;
  StereoRig rig_;
  FrontendConfig frontend_config_;
  const Trajectory* imu_motion_;
  double map_radius_m_;
  std::optional<loop::LoopCloser> closer_;
  loop::GlobalPoseGraph graph_;
  std::deque<StereoFrame> recent_frames_;
  std::optional<PendingKeyScan> pending_;
  std::optional<MapCorrection> correction_;
  std::optional<SE3> last_mapper_T_W_L_;   // the mapper's last output (corrected after a loop)
  SE3 T_odometry_mapper_;                  // lidar_odometry = T_odometry_mapper_ * mapper output
  bool corrected_ = false;
  std::optional<std::size_t> last_key_index_;  // graph index of the last key scan
  // The join checked by the mapper (LoopClosureConfig::join_registration): armed when the run re-localizes; the
  // correction is then handed to the mapper, and the next sweep is the first registered on the map.
  enum class JoinRegistration { kNone, kAwaitCorrection, kAwaitSweep };
  JoinRegistration join_registration_ = JoinRegistration::kNone;
  std::vector<std::size_t> resumed_map_loops_;  // positions in the graph of the map loops from the resume guess
  struct Relocalization {                      // map loops in a row that agree on T_map_run
    SE3 T_map_run;
    std::vector<loop::LoopCandidateRecord> loops;
  };
  std::optional<Relocalization> relocalization_;
  LoopClosureOutput out_;
};

}  // namespace vilslam
