#pragma once
// The library's entry point: a robot's drivers push sensor data from their threads, the modules of the paper's
// diagram run on threads of their own behind bounded queues (pipeline/stage.h: frontend, smoother, LiDAR
// mapping with loop closure), and every output comes back by a callback as soon as it exists. `vilslam run`
// drives it from a dataset (pipeline/offline_runner.h). docs/pipeline.md, "The System API".
#include <functional>
#include <memory>
#include <optional>

#include "common/calibration.h"
#include "common/types.h"
#include "loop/map_file.h"
#include "pipeline/run_types.h"
#include "vio/vio_status.h"

namespace vilslam {

// Each callback runs on the thread of the module that produced the output: keep it short, it holds that
// module up. Unset callbacks cost nothing.
struct SystemCallbacks {
  // vio and vil: T_W_I at each IMU sample, propagated from the newest optimized state on the pushing thread,
  // before the sample is queued, so it never waits for an optimization (none before initialization).
  std::function<void(const TimedPose&)> imu_pose;
  // vio and vil: T_W_I of each optimized stereo-frame state (smoother thread).
  std::function<void(const TimedPose&)> camera_state;
  // vio and vil: what the VIO went through at each state, and each loss (`lost_...`) as it is declared, the
  // rows of vio_status.csv (vio/vio_status.h; smoother thread).
  std::function<void(const VioStatusRecord&)> vio_status;
  // vil and lidar-only: each mapped sweep, the mapper's own pose and fit (LiDAR thread).
  std::function<void(const lidar::LidarMappingResult&)> lidar_pose;
  // vil: the same sweep's pose with the loop corrections known at that moment (LiDAR thread).
  std::function<void(const TimedPose&)> lidar_global_pose;
  // vil: every loop candidate examined, accepted or with the stage that rejected it (LiDAR thread).
  std::function<void(const loop::LoopCandidateRecord&)> loop_candidate;
  // vil and lidar-only: the newest mapped sweep's edge and planar features as registered (dewarped to the
  // sweep's end, in its L) with T_W_L; a sparse map to show (LiDAR thread).
  std::function<void(const TimedPose& T_W_L, const lidar::FeatureScan& features_L)> lidar_features;
};

class System {
 public:
  // calib: the rig as the estimator knows it, the camera-IMU time offset included (sensor times are moved to
  // the IMU clock inside). config.realtime.speed > 0 turns on the overload policy of pipeline/realtime.h
  // (push_stereo / push_scan drop when too many wait) and the live queue capacity.
  // map: the map of this run before a reset (pipeline/run_segments.h), to re-localize in as in config.load_map's
  // (docs/loop.md, "Map reuse", "Forced resets"), its last key frames verified at every query: the robot is near.
  // Throws InputError when the mode needs a sensor the calibration lacks, or a map without vil and loop closure.
  System(const RigCalibration& calib, const OfflineRunConfig& config, SystemCallbacks callbacks = {},
         std::optional<loop::SavedMap> map = std::nullopt);
  ~System();
  System(const System&) = delete;
  System& operator=(const System&) = delete;

  // The modules see the data in the order it was pushed; push in time order (IMU samples, stereo pairs and
  // sweeps interleaved as they were measured) and the outputs are deterministic. Safe from several threads
  // (each push is atomic), but their interleaving is then the threads'.
  void push_imu(const ImuSample& sample);
  // false: dropped by the overload policy (real-time mode only).
  bool push_stereo(StereoFrame frame);
  bool push_scan(LidarScan scan);

  // A module threw: later pushes are dropped, finish() rethrows its error.
  bool failed() const;
  // LiDAR mapping is lost (lidar/mapping_loss.h): it maps no more sweeps. A new System, given the map of this
  // one (finish(), pipeline/run_segments.h join_map), starts again and re-localizes in it (offline_runner.h).
  bool lidar_lost() const;
  // Waits until every module has handled what was pushed so far; pushing may go on afterwards. What the outputs
  // hold then depends on the pushed data only.
  void wait_idle();
  std::size_t dropped_frames() const;
  std::size_t dropped_sweeps() const;
  QueueDepths max_queue_depths() const;

  // Waits until every module has handled what was pushed, then returns everything collected (trajectories,
  // per-module timings, loop closure output); rethrows the first module error. Call once.
  OfflineRunResult finish();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace vilslam
