#pragma once
// IMU-rate propagation from the latest optimized state: the samples after it are preintegrated with its
// biases and the state is predicted with Forster eq. (44) at every new sample.
#include <optional>
#include <vector>

#include "common/calibration.h"
#include "common/types.h"
#include "vio/preintegration.h"
#include "vio/window_state.h"

namespace vilslam {

class Propagator {
 public:
  Propagator(const ImuNoise& noise, const Vec3& gravity_W) : noise_(noise), gravity_W_(gravity_W) {}

  // Anchors at x and integrates the buffered samples from x.t_ns to the last of them (if later).
  void reset(const NavState& x, const std::vector<ImuSample>& samples);
  // The state at sample.t_ns; sample must be later than the previous one.
  NavState add(const ImuSample& sample);
  // The state at the last integrated time (the anchor itself before any sample).
  NavState current() const;
  // The state at t_ns, not before the last integrated time, the last sample held after it.
  NavState state_at(TimeNs t_ns) const;

 private:
  ImuNoise noise_;
  Vec3 gravity_W_;
  NavState anchor_;
  std::optional<Preintegration> preint_;
  std::optional<ImuSample> last_;
  TimeNs last_t_ns_ = 0;
};

}  // namespace vilslam
