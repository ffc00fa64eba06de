#pragma once
// Fixed-lag smoother of the stereo VIO (paper Sec. "Optimization and marginalization"): the most recent
// N states, IMU pre-integration and bias factors between consecutive states, one structureless vision
// factor per landmark, and a prior from Schur-complement marginalization, solved by Levenberg-Marquardt.
#include <cstdint>
#include <deque>
#include <map>
#include <optional>
#include <set>
#include <vector>

#include "common/calibration.h"
#include "frontend/stereo_match.h"
#include "vio/dense_lm.h"
#include "vio/preintegration.h"
#include "vio/prior.h"
#include "vio/vision_factor.h"
#include "vio/window_state.h"

namespace vilslam {

struct SmootherConfig {
  int window_size = 10;                // N stereo frames
  double pixel_sigma_px = 1.0;         // visual measurement noise
  double gravity_m_s2 = 9.81;
  double outlier_normal_quantile = 2.326;  // chi-square test at 99 % (standard normal quantile)
  LmConfig lm;
};

struct SmootherStats {
  int landmarks = 0;          // landmarks with a vision factor in the last solve
  int rejected_landmarks = 0;  // landmarks dropped by the chi-square test so far
  int lm_iterations = 0;
  double final_cost = 0;
};

class Smoother {
 public:
  // focal_px converts the pixel noise into normalized coordinates.
  Smoother(const SmootherConfig& config, const StereoExtrinsics& extrinsics, const ImuNoise& noise, double focal_px);

  // Starts the window with x0 (prior standard deviations prior_sigma) and its frame's observations.
  void initialize(const NavState& x0, const Vec15& prior_sigma, const FrontendOutput& frame);
  // Adds the state at frame.t_ns, predicted from the newest one by `preint` (integrated from the newest
  // state's time with its biases), optimizes, and marginalizes the oldest state beyond N.
  void add_frame(const Preintegration& preint, const FrontendOutput& frame);

  // Re-solves the window (add_frame does this before marginalizing).
  void optimize();

  bool initialized() const { return !window_.empty(); }
  // Drops the window, its landmarks and its prior (the VIO lost track); initialize() starts again.
  void reset();
  // Throws std::logic_error before initialize() or after reset(): there is no newest state then.
  const NavState& newest() const;
  // Covariance of the newest state: its 15x15 block of the inverse of the window's H after the solve.
  const Mat15& newest_covariance() const { return newest_covariance_; }
  std::vector<NavState> window_states() const;
  const SmootherStats& stats() const { return stats_; }
  const PriorFactor& prior() const { return prior_; }
  Vec3 gravity_W() const { return Vec3(0, 0, -config_.gravity_m_s2); }

 private:
  struct Entry {
    std::uint64_t id = 0;
    NavState x;
    std::optional<Preintegration> from_previous;
  };
  struct TrackObservation {
    std::uint64_t state_id = 0;
    Eigen::Vector2d left_norm, right_norm;
  };

  void add_observations(std::uint64_t state_id, const FrontendOutput& frame);
  std::vector<LinearFactor> linearize(const std::vector<NavState>& states) const;
  std::vector<LinearFactor> imu_factors(const std::vector<NavState>& states, int j) const;
  std::optional<LinearFactor> vision_factor(const std::vector<TrackObservation>& track,
                                            const std::vector<NavState>& states) const;
  int reject_outliers(const std::vector<NavState>& states);
  void marginalize_oldest();
  int slot_of(std::uint64_t id) const;

  SmootherConfig config_;
  StereoExtrinsics extrinsics_;
  ImuNoise noise_;
  double sigma_norm_;
  std::deque<Entry> window_;
  std::map<std::uint64_t, std::vector<TrackObservation>> tracks_;
  std::set<std::uint64_t> rejected_tracks_;
  PriorFactor prior_;
  std::uint64_t next_id_ = 0;
  Mat15 newest_covariance_ = Mat15::Zero();
  SmootherStats stats_;
};

}  // namespace vilslam
