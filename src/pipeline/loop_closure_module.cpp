#include "pipeline/loop_closure_module.h"

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <limits>

#include "loop/loop_constraint.h"
#include "loop/registration_loop.h"

namespace vilslam {
namespace {

double elapsed_ms(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

constexpr TimeNs kRecentFramesNs = 2'000'000'000;  // stereo pairs kept as key image candidates
// After a reset: the map's last key frames verified at every query (about the last 3 m of the route).
constexpr std::size_t kResumeCandidates = 3;
constexpr double kResumeVelocityBaselineS = 0.1;  // the resume guess's velocity: the IMU motion's first 0.1 s

}  // namespace

LoopClosureModule::LoopClosureModule(const loop::LoopClosureConfig& config,
                                     const loop::GlobalPoseGraphConfig& graph_config,
                                     std::shared_ptr<const Vocabulary> vocabulary, const RigCalibration& calib,
                                     const FrontendConfig& frontend_config, const lidar::LidarConfig& lidar,
                                     const Trajectory* imu_motion)
    : config_(config), vocabulary_(std::move(vocabulary)), calib_(calib), rig_(make_stereo_rig(calib)),
      frontend_config_(frontend_config), imu_motion_(imu_motion), map_radius_m_(lidar.map.edges.max_distance_m),
      graph_(graph_config) {
  if (config_.enabled) closer_.emplace(config_, lidar, vocabulary_);
}

void LoopClosureModule::load_map(loop::SavedMap map, bool resume) {
  if (!closer_) throw std::invalid_argument("loading a map needs loop closure enabled");
  if (graph_.size() > 0) throw std::invalid_argument("a map is loaded before the first sweep");
  closer_->load_map(std::move(map.key_frames), std::move(map.poses), resume ? kResumeCandidates : 0);
}

void LoopClosureModule::stereo(const StereoFrame& frame) {
  if (!closer_) return;
  recent_frames_.push_back(frame);
  while (recent_frames_.front().t_ns < frame.t_ns - kRecentFramesNs) recent_frames_.pop_front();
  if (!pending_) return;
  if (const StereoFrame* image = key_image_for(pending_->scan_t_ns)) {
    add_key_frame(*pending_, *image);
    pending_.reset();
  } else if (ns_to_s(frame.t_ns - pending_->scan_t_ns) > config_.key_frames.max_image_scan_gap_s) {
    pending_.reset();  // no stereo pair near the key scan: it stays an ordinary scan
  }
}

// Paper: key images and key scans are associated by their timestamps.
const StereoFrame* LoopClosureModule::key_image_for(TimeNs scan_t_ns) const {
  const StereoFrame* nearest = nullptr;
  TimeNs best_gap_ns = std::numeric_limits<TimeNs>::max();
  for (const StereoFrame& f : recent_frames_) {
    const TimeNs gap_ns = std::llabs(f.t_ns - scan_t_ns);
    if (gap_ns < best_gap_ns) best_gap_ns = gap_ns, nearest = &f;
  }
  // A later pair may still come closer: decide only once one after the sweep's end is there.
  const bool later_seen = !recent_frames_.empty() && recent_frames_.back().t_ns >= scan_t_ns;
  if (!nearest || !later_seen || ns_to_s(best_gap_ns) > config_.key_frames.max_image_scan_gap_s) return nullptr;
  return nearest;
}

void LoopClosureModule::add_key_frame(const PendingKeyScan& scan, const StereoFrame& frame) {
  const Trajectory& poses = *imu_motion_;
  if (poses.size() < 2 || frame.t_ns < poses.front().t_ns) return;
  // The key image's camera in the key scan's frame, through the VIO motion between the two instants. The
  // IMU-rate poses reach the sweep's end; an image up to the gap after it extrapolates their last step.
  const auto T_O_I_at = [&poses](TimeNs t_ns) {
    if (t_ns <= poses.back().t_ns) return pose_at(poses, t_ns);
    const TimedPose& a = poses[poses.size() - 2];
    const TimedPose& b = poses.back();
    return interpolate(a.T_W_B, b.T_W_B, double(t_ns - a.t_ns) / double(b.t_ns - a.t_ns));
  };
  auto start = std::chrono::steady_clock::now();
  loop::KeyFrame key_frame;
  key_frame.pose_index = scan.pose_index;
  key_frame.scan_t_ns = scan.scan_t_ns;
  key_frame.T_L_C0 = (T_O_I_at(scan.scan_t_ns) * calib_.T_I_L).inverse() * T_O_I_at(frame.t_ns) * calib_.T_I_C0;
  key_frame.image = loop::make_key_image(frame, rig_, frontend_config_, *vocabulary_);
  key_frame.features_L = scan.features_L;
  out_.key_frame_ms.push_back(elapsed_ms(start));
  last_key_index_ = scan.pose_index;

  start = std::chrono::steady_clock::now();
  closer_->set_resume_guess(resume_guess(key_frame.scan_t_ns));
  const auto records = closer_->add_and_detect(std::move(key_frame), [this](std::size_t i) { return graph_.pose(i); });
  out_.detection_ms.push_back(elapsed_ms(start));
  bool loop_found = false;
  for (const loop::LoopCandidateRecord& r : records) {
    out_.candidates.push_back(r);
    if (!r.accepted()) continue;
    if (r.map_candidate) {
      loop_found = add_map_loop(r) || loop_found;
      continue;
    }
    graph_.add_loop(r.candidate_pose_index, r.query_pose_index, r.T_Lu_Lv, r.information);
    loop_found = true;
  }
  if (!loop_found) return;
  start = std::chrono::steady_clock::now();
  graph_.optimize();
  // The mapper resumes from its latest pose, corrected; lidar.tum stays continuous.
  correction_ = correction_at(graph_.size() - 1);
  out_.correction_ms.push_back(elapsed_ms(start));
  T_odometry_mapper_ = out_.lidar_odometry.back().T_W_B * correction_->T_W_L_last.inverse();
  last_mapper_T_W_L_ = correction_->T_W_L_last;
  corrected_ = true;
}

bool LoopClosureModule::add_map_loop(const loop::LoopCandidateRecord& r) {
  const auto T_map_Lu = [this](const loop::LoopCandidateRecord& loop) {
    return closer_->map_poses()[loop.candidate_pose_index].T_W_B;
  };
  if (relocalized()) {
    graph_.add_map_loop(T_map_Lu(r), r.query_pose_index, r.T_Lu_Lv, r.information);
    return true;
  }
  // Where this run's frame lies in the map by this loop: T_map_run = T_map_Lu T_Lu_Lv (T_run_Lv)^-1.
  const SE3 T_map_run = T_map_Lu(r) * r.T_Lu_Lv * graph_.pose(r.query_pose_index).inverse();
  const bool agrees = relocalization_ && [&] {
    const loop::PoseDifference d = loop::pose_difference(relocalization_->T_map_run, T_map_run);
    return d.translation_m <= config_.relocalization_agreement_m && d.rotation_rad <= config_.relocalization_agreement_rad;
  }();
  if (!agrees) relocalization_ = Relocalization{};
  relocalization_->T_map_run = T_map_run;
  relocalization_->loops.push_back(r);
  if (static_cast<int>(relocalization_->loops.size()) < config_.relocalization_loops) return false;
  // Re-localized: the graph moves into the map's frame by the latest vote and takes the agreeing loops.
  graph_.transform(T_map_run);
  for (const loop::LoopCandidateRecord& loop : relocalization_->loops) {
    if (loop.resumed) resumed_map_loops_.push_back(graph_.map_loops());
    graph_.add_map_loop(T_map_Lu(loop), loop.query_pose_index, loop.T_Lu_Lv, loop.information);
  }
  out_.relocalized_t_ns = r.query_t_ns;
  if (config_.join_registration) join_registration_ = JoinRegistration::kAwaitCorrection;
  out_.T_map_run = T_map_run;
  relocalization_.reset();
  closer_->set_in_map_frame(true);
  return true;
}

std::optional<SE3> LoopClosureModule::resume_guess(TimeNs query_t_ns) const {
  const Trajectory& imu = *imu_motion_;  // this segment's jump-free IMU motion T_O_I, from its first state on
  if (closer_->resume_candidates() == 0 || relocalized() || graph_.size() == 0 || imu.size() < 2) return std::nullopt;
  const TimedPose& first = graph_.trajectory().front();
  if (ns_to_s(query_t_ns - first.t_ns) > config_.resume_window_s || first.t_ns < imu.front().t_ns) return std::nullopt;
  // The LiDAR pose at the segment's first IMU pose (before its first sweep's), by the IMU motion between the two;
  // from there back to the map's last pose at the IMU's first velocity (a fraction of a second).
  const auto T_O_L = [&](const SE3& T_O_I) { return T_O_I * calib_.T_I_L; };
  const TimedPose& a = imu.front();
  std::size_t k = 1;
  while (k + 1 < imu.size() && ns_to_s(imu[k].t_ns - a.t_ns) < kResumeVelocityBaselineS) ++k;
  const TimedPose& b = imu[k];
  const SE3 T_run_La = first.T_W_B * T_O_L(pose_at(imu, first.t_ns)).inverse() * T_O_L(a.T_W_B);
  const Vec6 motion = (T_O_L(a.T_W_B).inverse() * T_O_L(b.T_W_B)).log();
  const TimedPose& map_last = closer_->map_poses().back();
  const double gap_ratio = double(a.t_ns - map_last.t_ns) / double(b.t_ns - a.t_ns);
  const SE3 T_map_run = map_last.T_W_B * SE3::exp(motion * gap_ratio) * T_run_La.inverse();
  // Both frames are the VIO's, gravity-aligned: the guess keeps its yaw only, not the tilt the first poses of a
  // just-aligned window still carry.
  const Mat3& R = T_map_run.rotation();
  const Mat3 R_yaw = so3::rot_z(so3::yaw_rad(R));
  return SE3(R_yaw, T_map_run.translation());
}

MapCorrection LoopClosureModule::correction_at(std::size_t pose_index) const {
  MapCorrection c;
  c.T_W_L_last = graph_.pose(pose_index);
  const auto add_if_near = [&](const loop::KeyFrame& kf, const SE3& T_W_L) {
    if ((T_W_L.translation() - c.T_W_L_last.translation()).norm() <= map_radius_m_) {
      c.key_scans.push_back({&kf.features_L, T_W_L});
    }
  };
  // Once re-localized, the saved key scans around the pose join this run's (all in the map's frame).
  if (relocalized()) {
    for (const loop::KeyFrame& kf : closer_->map_key_frames()) add_if_near(kf, closer_->map_poses()[kf.pose_index].T_W_B);
  }
  for (const loop::KeyFrame& kf : closer_->key_frames()) add_if_near(kf, graph_.pose(kf.pose_index));
  return c;
}

void LoopClosureModule::scan_mapped(const lidar::LidarMappingResult& mapped, const lidar::FeatureScan& features_L) {
  // lidar.tum: the mapper's motion composed, continuous across the corrections.
  out_.lidar_odometry.push_back({mapped.t_ns, corrected_ ? T_odometry_mapper_ * mapped.T_W_L : mapped.T_W_L});
  // The first sweep on the map after re-localizing: its odometry factor is the mapper's prediction, and its
  // registration on the map a loop (loop/registration_loop.h) that replaces the loops from the resume guess, so the
  // jump from the one to the other moves the segment before it instead of staying in the trajectory as motion.
  std::optional<loop::RegistrationLoop> join_loop;
  if (join_registration_ == JoinRegistration::kAwaitSweep) {
    join_registration_ = JoinRegistration::kNone;
    // Along the directions the registration left free, the resume guess's sigmas (what placed the segment there).
    const loop::RegistrationLoopSigmas sigmas{config_.icp_sigma_m, config_.loop_sigma_m, config_.loop_sigma_rad,
                                              config_.resume_sigma_m, config_.resume_sigma_rad};
    join_loop = loop::registration_loop(closer_->map_key_frames(), closer_->map_poses(), mapped.T_W_L,
                                        mapped.information, mapped.degenerate_directions, map_radius_m_, sigmas);
  }
  std::size_t index = 0;
  if (join_loop) {
    index = graph_.add_odometry(mapped.t_ns, mapped.T_prev_predicted);
  } else if (last_mapper_T_W_L_) {
    index = graph_.add_odometry(mapped.t_ns, last_mapper_T_W_L_->inverse() * mapped.T_W_L, mapped.degenerate_directions);
  } else {
    index = graph_.add_first_pose(mapped.t_ns, mapped.T_W_L);
  }
  if (mapped.up_L_prior) graph_.set_up_direction(index, *mapped.up_L_prior, mapped.up_L_prior_sigma_rad);
  if (join_loop) {
    const auto start = std::chrono::steady_clock::now();
    graph_.add_map_loop(closer_->map_poses()[join_loop->map_pose_index].T_W_B, index, join_loop->T_Lu_Lv,
                        join_loop->information);
    // The loops verified from the resume guess stood in until the mapper measured the join on the whole map: ICP
    // of single key scans, from a guess, against the registration of this sweep on all the key scans around it.
    graph_.remove_map_loops(resumed_map_loops_);
    resumed_map_loops_.clear();
    graph_.optimize();
    out_.correction_ms.push_back(elapsed_ms(start));
  }
  last_mapper_T_W_L_ = mapped.T_W_L;
  out_.lidar_global.push_back({mapped.t_ns, mapped.T_W_L});  // as published now
  if (!closer_ || pending_) return;
  if (last_key_index_ && !loop::is_new_key_frame(graph_.pose(*last_key_index_), graph_.pose(index - 1),
                                                  graph_.pose(index), ns_to_s(mapped.t_ns - graph_.trajectory()[index - 1].t_ns),
                                                  config_.key_frames)) {
    return;
  }
  pending_ = PendingKeyScan{mapped.t_ns, index, features_L};
  if (const StereoFrame* image = key_image_for(mapped.t_ns)) {
    add_key_frame(*pending_, *image);
    pending_.reset();
  }
}

std::optional<MapCorrection> LoopClosureModule::take_correction() {
  std::optional<MapCorrection> c;
  std::swap(c, correction_);
  if (c && join_registration_ == JoinRegistration::kAwaitCorrection) join_registration_ = JoinRegistration::kAwaitSweep;
  return c;
}

LoopClosureOutput LoopClosureModule::finish() {
  out_.key_frames = closer_ ? closer_->key_frames().size() : 0;
  out_.map_loops = graph_.map_loops();
  if (closer_) out_.key_frame_data = closer_->release_key_frames();
  if (corrected_) {
    const loop::CorrectionSummary final_solve = graph_.optimize_final();
    if (final_solve.variables > 0) out_.final_solve_ms.push_back(final_solve.solve_ms);
  }
  out_.lidar_final = graph_.size() > 0 ? graph_.trajectory() : Trajectory{};
  if (!corrected_) out_.lidar_final = out_.lidar_global;  // no loop: the odometry is final
  return std::move(out_);
}

}  // namespace vilslam
