#pragma once
// The stateful LiDAR mapping of the paper (Sec. "Lidar mapping"): per sweep, LOAM features from the raw
// scan, dewarping to the scan end with the motion prior, the initial guess L*_{k+1} = L_k T_trans,
// scan-to-map registration with Zhang et al. solution remapping, and insertion into the local feature map.
// Without a prior it is the LOAM baseline: a constant-velocity motion model.
#include <deque>
#include <functional>
#include <optional>
#include <string>

#include "common/lie.h"
#include "common/types.h"
#include "lidar/feature_map.h"
#include "lidar/azimuth_times.h"
#include "lidar/lidar_config.h"
#include "lidar/mapping_loss.h"
#include "lidar/model_deviation.h"
#include "lidar/registration.h"

namespace vilslam::lidar {

struct LidarMapperConfig {
  LidarConfig lidar;  // rings, features, map (voxel sizes, radius max_distance_m), registration
  bool dewarp = true; // move feature points to the scan end before registration (paper eq. for P~_i)
  // Without a prior: dewarp again with the sweep's registered motion and register once more.
  bool lidar_only_redewarp = true;
  MappingLossConfig loss;  // which registered sweeps are rejected, and when the mapper is lost

  LidarMapperConfig();
};

// The sections of lidar_yaml_fields plus `mapper` (dewarp, lidar_only_redewarp) and `loss`, bound to c's fields: the
// `lidar_mapper:` section of a run config (pipeline/run_config.h). Validate with validate_lidar_config.
YamlFields lidar_mapper_yaml_fields(LidarMapperConfig& c);

struct LidarMappingResult {
  TimeNs t_ns = 0;  // the scan end t_{k+1}, the instant of T_W_L
  SE3 T_W_L;
  bool degenerate = false;             // some direction was below the degeneracy threshold
  std::vector<Vec6> degenerate_directions;  // those directions, unit [rho; phi] in L (the prior's motion kept)
  std::optional<Vec3> up_L_prior;      // the prior's up direction R_W_L^T e_z at t_ns (VIO: against gravity), if any
  double up_L_prior_sigma_rad = 0.0;   // the prior's tilt standard deviation, when known (process())
  Vec6 information_eigenvalues = Vec6::Zero();  // of J^T J at the solution, ascending
  Mat6 information = Mat6::Zero();     // J^T J at the solution, [rho; phi] in L (per m^2 of point residual; the
                                       // tilt prior's share included, as in the degeneracy analysis)
  SE3 T_prev_predicted;                // the motion prediction T_trans from the previous sweep's pose (identity first)
  double rms_residual_m = 0.0;         // registration fit (RegistrationResult); 0 for the first sweep
  double matched_fraction = 0.0;
  double inlier_fraction = 0.0;
  double time_ms = 0.0;                // wall time of process(), for reporting only
  int num_edge_features = 0;           // extracted from the sweep
  int num_surface_features = 0;
  // For the sweep's status (lidar/mapping_status.h): seconds with no sweep before this one (missing sweeps),
  // whether a VIO prior gave the motion, whether the registration converged, and how far it moved the pose
  // from the motion's prediction L_k T_trans (a jump the prior contradicts).
  double gap_s = 0.0;
  bool vio_prior = false;
  bool converged = true;
  double correction_m = 0.0;
  double correction_deg = 0.0;
  // Rejected (lidar/mapping_loss.h): T_W_L is where the registration ended, not the sweep's pose, and the sweep
  // is not in the map; the mapper's last pose stays the one before it.
  MappingLoss loss = MappingLoss::kNone;
  bool reanchored = false;  // the sweep began a fresh map at its predicted pose (LidarMapper::reanchor)
};

class LidarMapper {
 public:
  // sweep_period_ns: the sensor's nominal sweep period; a sweep without per-point times (one instant) is taken
  // to span it before its stamp when its gap to the previous sweep is measured (0: such a sweep spans nothing).
  // spinning: the sensor's traits show a spinning head (lidar/sensor_traits.h), so a sweep without per-point
  // times may take them from its azimuths at that period; whether it should is decided by the first moving sweeps
  // (azimuth_clock_, lidar/azimuth_times.h): the sweeps of a spinning head may come deskewed already.
  LidarMapper(const LidarMapperConfig& config, const SE3& T_I_L, TimeNs sweep_period_ns = 0, bool spinning = false);

  // T_W_I_prior: IMU-rate VIO pose at any time covering [scan.t_ns, scan end]; an empty function gives
  // LiDAR-only mapping. T_O_I_dewarp: when given, the sweep is dewarped with its relative poses instead
  // (the VIO's jump-free IMU motion, vio/vio.h); T_W_I_prior still gives the motion between sweeps.
  // prior_tilt_sigma_rad: the prior's tilt standard deviation at the scan end when known (the VIO's), which
  // weakens the registration's tilt prior (lidar/registration.h). A rejected sweep (result.loss) leaves the
  // mapper as it was: the next sweep is predicted from the last one it kept. Throws InputError on an empty scan or a scan
  // ending before the previous one.
  LidarMappingResult process(const LidarScan& scan, const std::function<SE3(TimeNs)>& T_W_I_prior,
                             const std::function<SE3(TimeNs)>& T_O_I_dewarp = {}, double prior_tilt_sigma_rad = 0.0);

  const FeatureMap& map() const { return map_; }
  // Whether sweeps without point times took azimuth times: "yes" or "no" once the first moving sweeps voted,
  // "undecided" before (they are instants meanwhile).
  std::string azimuth_times() const;
  // The last sweep's features as registered: dewarped to its end, in its LiDAR frame.
  const FeatureScan& last_features() const { return last_features_; }

  // Loop correction (paper, "Re-localization"): the last pose becomes T_W_L_last and the feature map is
  // rebuilt from the scans at their corrected poses, so the next sweeps register against the corrected,
  // revisited map. Motion priors stay relative, so mapping resumes in the corrected frame.
  void relocalize(const SE3& T_W_L_last, const std::vector<PosedFeatureScan>& scans);

  // The map no longer places the sweeps (the loss check rejected several in a row): it is dropped, and the next
  // sweep starts a fresh one at its predicted pose (the last kept pose and the motion since), flagged reanchored.
  void reanchor();

 private:
  struct Previous {
    TimeNs end_t_ns = 0;
    SE3 T_W_L;                        // the optimized L_k
    std::optional<SE3> T_W_L_prior;   // the prior's LiDAR pose at end_t_ns, when there was one
    std::optional<Vec6> motion;       // log(L_{k-1}^-1 L_k), for the constant-velocity model
    TimeNs motion_duration_ns = 0;
  };

  // T_trans: the prior's motion since the previous scan end, else the constant-velocity extrapolation.
  SE3 motion_since_previous(TimeNs end_t_ns, const std::optional<SE3>& T_W_L_prior_end) const;
  // LiDAR-only: dewarps the sweep with the motion of its first registration T_W_L and registers it again.
  RegistrationResult reregister_lidar_only(const FeatureScan& raw, TimeNs end_t_ns, const SE3& T_W_L,
                                           FeatureScan& features, const RegistrationConfig& config);
  // The registration without a motion prior: its robust kernel at least the constant-velocity model's observed
  // deviation / 3 (KISS-ICP), and as many more outer iterations as the kernel widened, up to 5x.
  RegistrationConfig registration_without_prior() const;
  // A spinning sweep without per-point times, registered as one instant (instant.T_W_L): one vote of the azimuth
  // clock, from the fit of the same sweep with azimuth times dewarped by its registered motion.
  // points_L: the sweep's features at its end.
  void vote_azimuth_clock(const LidarScan& scan, const std::vector<Vec3>& points_L, const LidarMappingResult& instant);

  LidarMapperConfig config_;
  SE3 T_I_L_;
  TimeNs sweep_period_ns_;
  bool spinning_;
  AzimuthClockVote azimuth_clock_;
  ModelDeviation model_deviation_;  // of the constant-velocity predictions (sweeps without a prior)
  FeatureMap map_;
  std::optional<Previous> previous_;
  // The last poses registered with a prior (end time, T_W_L): their mean motion predicts a VIO outage's sweeps.
  static constexpr std::size_t kAidedPoses = 11;
  std::deque<std::pair<TimeNs, SE3>> aided_poses_;
  std::optional<FeatureScan> first_raw_;
  bool reanchored_ = false;  // the map was dropped: the next sweep starts it again
  FeatureScan last_features_;  // LiDAR-only: the first sweep's features until its motion is known
};

}  // namespace vilslam::lidar
