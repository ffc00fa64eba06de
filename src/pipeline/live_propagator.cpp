#include "pipeline/live_propagator.h"

#include <algorithm>

namespace vilslam {

void LivePropagator::anchor(const NavState& newest) {
  const std::lock_guard<std::mutex> lock(mutex_);
  new_anchor_ = newest;
  lost_ = false;
}

void LivePropagator::lost() {
  const std::lock_guard<std::mutex> lock(mutex_);
  new_anchor_.reset();
  lost_ = true;
}

std::optional<SE3> LivePropagator::add(const ImuSample& sample) {
  std::optional<NavState> anchor;
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    std::swap(anchor, new_anchor_);
    if (lost_) anchor_t_ns_.reset();
    lost_ = false;
  }
  samples_.push_back(sample);
  if (anchor) {
    drop_samples_before(samples_, anchor->t_ns);
    propagator_.reset(*anchor, samples_);
    anchor_t_ns_ = anchor->t_ns;
  } else if (anchor_t_ns_) {
    propagator_.add(sample);
  } else {
    samples_.erase(samples_.begin(), samples_.end() - 1);  // nothing to propagate from yet: keep the last only
  }
  if (!anchor_t_ns_ || sample.t_ns <= *anchor_t_ns_) return std::nullopt;
  return propagator_.current().T_W_I();
}

}  // namespace vilslam
