#include "pipeline/realtime.h"

#include <stdexcept>
#include <thread>

namespace vilslam {

SensorClock::SensorClock(TimeNs first_t_ns, double speed) : first_t_ns_(first_t_ns), speed_(speed), start_(Clock::now()) {
  if (!(speed > 0.0)) throw std::invalid_argument("real-time speed must be positive");
}

SensorClock::Clock::time_point SensorClock::due(TimeNs t_ns) const {
  const double wall_ns = double(t_ns - first_t_ns_) / speed_;
  return start_ + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double, std::nano>(wall_ns));
}

double SensorClock::wait_until(TimeNs t_ns) const {
  const Clock::time_point at = due(t_ns);
  const Clock::time_point now = Clock::now();
  if (now >= at) return std::chrono::duration<double, std::milli>(now - at).count();
  std::this_thread::sleep_until(at);
  return 0.0;
}

double SensorClock::since_ms(TimeNs t_ns) const {
  return std::chrono::duration<double, std::milli>(Clock::now() - due(t_ns)).count();
}

}  // namespace vilslam
