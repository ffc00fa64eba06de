#pragma once
// Feeds LiDAR sweeps to the mapper. With the VIO (vil mode) a sweep waits until the IMU-rate VIO poses
// reach its end, then maps with those poses interpolated as the motion prior (paper, "Lidar mapping");
// without it (lidar-only) each sweep is mapped at once with the constant-velocity model. With a loop
// closure module every mapped sweep goes to it, and its map corrections go back to the mapper.
#include <cstddef>
#include <deque>
#include <optional>
#include <vector>

#include "common/calibration.h"
#include "common/types.h"
#include "lidar/lidar_mapper.h"
#include "lidar/sensor_traits.h"
#include "pipeline/loop_closure_module.h"

namespace vilslam {

class LidarFeeder {
 public:
  // imu_poses: the VIO's IMU-rate poses as they grow (vil), or nullptr for LiDAR-only mapping; imu_motion:
  // the same samples' jump-free poses T_O_I (vio/vio.h), which dewarp the sweeps, or nullptr; imu_tilt_sigma_rad:
  // the same samples' tilt standard deviations (VioImuOutput), which weigh the tilt priors, or nullptr.
  // results: every sweep mapped; rejected: every sweep the mapper rejected (lidar/mapping_loss.h), which neither
  // the results nor loop closure see. loop: the loop closure module, or nullptr. reanchor_when_lost: when the
  // mapper rejects loss.lost_after_rejected sweeps in a row it starts a fresh local map at the next sweep's
  // predicted pose and maps on (status "reanchored"); false: it is lost and maps nothing more (the run resets).
  LidarFeeder(const lidar::LidarMapperConfig& config, const RigCalibration& calib, const Trajectory* imu_poses,
              const Trajectory* imu_motion, const std::vector<double>* imu_tilt_sigma_rad,
              std::vector<lidar::LidarMappingResult>* results, std::vector<lidar::LidarMappingResult>* rejected,
              LoopClosureModule* loop = nullptr, bool reanchor_when_lost = false);

  void scan(LidarScan scan);
  // Maps the waiting sweeps that the IMU-rate poses now cover.
  void poses_advanced();
  // The VIO lost track after the poses so far (vio/vio.h VioLossEvent). Sweeps wait until its restarted window
  // publishes poses (from the window's first frame on, once it aligned: about alignment.frames frames later);
  // those that began before that window are then mapped from the LiDAR alone (constant velocity), the later ones
  // with the new poses. The first sweep after a restart takes no motion across it (the mapper's prior is relative).
  void vio_lost();
  // At the end of the data: poses_advanced(), and a VIO lost for good leaves no sweep waiting (mapped LiDAR-only).
  void finish();
  // Sweeps no VIO pose covers (before initialization or after the last pose), and those after the mapper was
  // lost, are left unmapped.
  std::size_t unmapped_scans() const { return unmapped_ + waiting_.size(); }
  // The end of the sweep whose rejection made the mapper lost (loss.lost_after_rejected in a row): it maps
  // nothing more.
  std::optional<TimeNs> lost_t_ns() const { return mapper_lost_t_ns_; }
  // Sweeps still waiting for the VIO poses to reach their end.
  std::size_t waiting_scans() const { return waiting_.size(); }
  // The newest mapped sweep's features as registered (lidar/lidar_mapper.h).
  const lidar::FeatureScan& last_features() const { return mapper_->last_features(); }
  // The sensor as the run read it (lidar_sensor.txt): its traits, off the first sweep (lidar/sensor_traits.h),
  // and "lidar_azimuth_times: yes|no|undecided" for sweeps without point times of a spinning head
  // (lidar_mapper.h). Empty before a sweep was read.
  std::string sensor_report() const;

 private:
  void map(const LidarScan& scan, const std::function<SE3(TimeNs)>& T_W_I_prior,
           const std::function<SE3(TimeNs)>& T_O_I_dewarp, double prior_tilt_sigma_rad = 0.0);

  // Reads the sensor's traits off the first sweep and builds the mapper for them (with too few returns to read
  // them: the config as given).
  void know_sensor(const LidarScan& scan);

  // The mapper may give sweeps without point times azimuth times (lidar_mapper.h): a spinning head, dewarping on.
  bool azimuth_clock_possible() const;
  // The end of scan's sweep, or where it ends once the mapper gives it azimuth times (lidar_mapper.h).
  TimeNs latest_end_t_ns(const LidarScan& scan) const;

  lidar::LidarMapperConfig config_;  // as given; the mapper's is adapted to the sensor's traits
  std::optional<lidar::SensorTraits> traits_;
  std::optional<lidar::LidarMapper> mapper_;
  SE3 T_I_L_;
  TimeNs offset_ns_;
  double rate_hz_;  // the calibration's sweep rate
  bool dewarp_;
  const Trajectory* imu_poses_;
  const Trajectory* imu_motion_;
  const std::vector<double>* imu_tilt_sigma_rad_;
  std::vector<lidar::LidarMappingResult>* results_;
  std::vector<lidar::LidarMappingResult>* rejected_;
  LoopClosureModule* loop_;
  int lost_after_rejected_;
  bool reanchor_when_lost_;
  int rejected_in_a_row_ = 0;
  std::optional<TimeNs> mapper_lost_t_ns_;
  std::deque<LidarScan> waiting_;
  std::size_t unmapped_ = 0;
  std::optional<std::size_t> lost_after_;   // while the VIO is lost: the number of poses it published before
  std::optional<TimeNs> restarted_t_ns_;    // the newest restarted window's first pose
};

}  // namespace vilslam
