#pragma once
// Real-time mode: the IMU-rate pose published the moment its sample arrives, propagated on the reader's thread
// from the newest optimized state the smoother handed over (VINS-Fusion does the same in its IMU callback).
// The smoother's own propagation, which the LiDAR side uses, waits behind its optimization; this one does not.
#include <mutex>
#include <optional>
#include <vector>

#include "common/calibration.h"
#include "common/types.h"
#include "vio/propagator.h"

namespace vilslam {

class LivePropagator {
 public:
  LivePropagator(const ImuNoise& noise, const Vec3& gravity_W) : propagator_(noise, gravity_W) {}

  // From the smoother's thread: a new optimized state; the next sample re-anchors on it.
  void anchor(const NavState& newest);
  // From the smoother's thread: the VIO lost track; no pose is published until the next anchor.
  void lost();
  // From the reader's thread, in time order: the pose T_W_I at the sample, once a state is anchored before it.
  std::optional<SE3> add(const ImuSample& sample);

 private:
  std::mutex mutex_;
  std::optional<NavState> new_anchor_;  // handed over, not yet applied
  bool lost_ = false;                   // handed over, not yet applied

  Propagator propagator_;               // the reader's thread only, from here on
  std::optional<TimeNs> anchor_t_ns_;
  std::vector<ImuSample> samples_;      // from the last one at or before the anchor on
};

}  // namespace vilslam
