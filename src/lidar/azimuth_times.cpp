#include "lidar/azimuth_times.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

namespace vilslam::lidar {
namespace {

constexpr double kTwoPi = 2.0 * M_PI;
constexpr double kSeamRad = 5.0 * M_PI / 180.0;  // near the start azimuth the file order decides
constexpr double kMinStepRad = 1e-4;             // smaller steps: points of one firing (float noise), no spin
constexpr double kMaxStepRad = 0.1;              // larger steps between consecutive points are gaps, not spin

// The group a point's order is counted in: its ring when the sweep has a ring field.
std::size_t group_of(const LidarScan& scan, const LidarPoint& p) { return scan.has_ring ? p.ring : 0; }

}  // namespace

bool has_point_times(const LidarScan& scan) {
  return std::any_of(scan.points.begin(), scan.points.end(), [](const LidarPoint& p) { return p.t_offset_s != 0.0f; });
}

void assign_azimuth_times(LidarScan& scan, double sweep_period_s) {
  if (!(sweep_period_s > 0.0)) throw std::invalid_argument("assign_azimuth_times needs a positive sweep period");
  std::size_t groups = 1;
  for (const LidarPoint& p : scan.points) groups = std::max(groups, group_of(scan, p) + 1);
  std::vector<double> start_rad(groups), previous_rad(groups);
  std::vector<std::size_t> count(groups, 0);
  std::vector<double> azimuth_rad(scan.points.size());
  long spin_votes = 0;
  for (std::size_t i = 0; i < scan.points.size(); ++i) {
    const LidarPoint& p = scan.points[i];
    const std::size_t g = group_of(scan, p);
    azimuth_rad[i] = std::atan2(p.y, p.x);
    if (count[g] == 0) {
      start_rad[g] = azimuth_rad[i];
    } else {
      const double step = std::remainder(azimuth_rad[i] - previous_rad[g], kTwoPi);
      if (std::abs(step) > kMinStepRad && std::abs(step) < kMaxStepRad) spin_votes += step > 0.0 ? 1 : -1;
    }
    previous_rad[g] = azimuth_rad[i];
    ++count[g];
  }
  const double spin = spin_votes > 0 ? 1.0 : -1.0;  // +1: azimuth grows with time (counter-clockwise)

  std::vector<std::size_t> seen(groups, 0);
  for (std::size_t i = 0; i < scan.points.size(); ++i) {
    LidarPoint& p = scan.points[i];
    const std::size_t g = group_of(scan, p);
    double swept_rad = spin * (azimuth_rad[i] - start_rad[g]);
    swept_rad -= kTwoPi * std::floor(swept_rad / kTwoPi);  // [0, 2 pi)
    const bool early_in_file = 2 * seen[g]++ < count[g];
    if (swept_rad > kTwoPi - kSeamRad && early_in_file) swept_rad = 0.0;  // just behind the start: opens the sweep
    if (swept_rad < kSeamRad && !early_in_file) swept_rad = kTwoPi;        // past a full turn: closes it
    p.t_offset_s = static_cast<float>(swept_rad / kTwoPi * sweep_period_s);
  }
}

void AzimuthClockVote::vote(double rms_timed_m, double rms_instant_m) {
  if (state_ != State::kUndecided) return;
  ++votes_;
  timed_better_ += rms_timed_m < rms_instant_m;
  if (votes_ == kVotes) state_ = 2 * timed_better_ > kVotes ? State::kTimed : State::kInstant;
}

bool fill_missing_point_times(LidarScan& scan, const SensorTraits& traits, double rate_hz) {
  if (!traits.spinning() || has_point_times(scan)) return false;
  assign_azimuth_times(scan, 1.0 / rate_hz);
  return true;
}

}  // namespace vilslam::lidar
