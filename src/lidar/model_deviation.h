#pragma once
// The motion model's observed deviation (KISS-ICP's adaptive threshold, Vizzo et al. 2023, Sec. III-C): without a
// motion prior a sweep is predicted by the constant-velocity model, and how far the registrations moved those
// predictions tells how wide the robust kernel must be to reach the right surfaces. A hand-held sensor at 2 Hz
// is corrected by 14 deg rms (the real BALM sequence), a simulated robot at 10 Hz by a few tenths of a degree.
#include <vector>

#include "common/lie.h"

namespace vilslam::lidar {

class ModelDeviation {
 public:
  // One registered sweep: points_L its features at the sweep end, correction the pose change from the prediction
  // to the registration, motion the registered motion since the previous sweep. A sweep that moved its points by
  // less than kMinMotion_m rms does not count (at rest the model cannot err, and would narrow the kernel).
  void add(const std::vector<Vec3>& points_L, const SE3& correction, const SE3& motion);
  // Root mean square of the counted sweeps' deviations: each the rms displacement of its points by its
  // correction. 0 before any sweep counted.
  double sigma_m() const;

  static constexpr double kMinMotion_m = 0.1;

 private:
  double sum_sq_m2_ = 0.0;
  int count_ = 0;
};

// The rms displacement of points_L by T (their distance from T * p_L).
double rms_displacement_m(const std::vector<Vec3>& points_L, const SE3& T);

}  // namespace vilslam::lidar
