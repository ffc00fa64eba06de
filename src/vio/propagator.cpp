#include "vio/propagator.h"

#include <stdexcept>

#include "vio/imu_factor.h"

namespace vilslam {

void Propagator::reset(const NavState& x, const std::vector<ImuSample>& samples) {
  anchor_ = x;
  preint_.emplace(x.bias_gyro_rad_s, x.bias_accel_m_s2, noise_);
  last_t_ns_ = x.t_ns;
  last_.reset();
  if (samples.empty()) return;
  last_ = samples.back();
  if (samples.back().t_ns > x.t_ns) {
    integrate_samples(samples, x.t_ns, samples.back().t_ns, *preint_);
    last_t_ns_ = samples.back().t_ns;
  }
}

NavState Propagator::add(const ImuSample& sample) {
  if (!preint_) throw std::logic_error("Propagator::add before reset");
  if (last_ && sample.t_ns <= last_->t_ns) throw std::invalid_argument("Propagator::add: sample not after the last");
  if (sample.t_ns > last_t_ns_) {
    // Midpoint of the segment [last_t, t] on the line between the last sample and this one.
    std::vector<ImuSample> pair;
    if (last_) pair.push_back(*last_);
    pair.push_back(sample);
    integrate_samples(pair, last_t_ns_, sample.t_ns, *preint_);
    last_t_ns_ = sample.t_ns;
  }
  last_ = sample;
  return current();
}

NavState Propagator::state_at(TimeNs t_ns) const {
  if (!preint_) throw std::logic_error("Propagator::state_at before reset");
  if (t_ns < last_t_ns_) throw std::invalid_argument("Propagator::state_at: before the last integrated time");
  if (t_ns == last_t_ns_ || !last_) return current();
  Preintegration preint = *preint_;
  integrate_samples({*last_}, last_t_ns_, t_ns, preint);
  NavState x = predict_state(preint, anchor_, gravity_W_);
  x.t_ns = t_ns;
  return x;
}

NavState Propagator::current() const {
  if (!preint_) throw std::logic_error("Propagator::current before reset");
  NavState x = predict_state(*preint_, anchor_, gravity_W_);
  x.t_ns = last_t_ns_;
  return x;
}

}  // namespace vilslam
