#include "lidar/model_deviation.h"

#include <cmath>

namespace vilslam::lidar {

double rms_displacement_m(const std::vector<Vec3>& points_L, const SE3& T) {
  if (points_L.empty()) return 0.0;
  double sum_sq = 0.0;
  for (const Vec3& p : points_L) sum_sq += (T * p - p).squaredNorm();
  return std::sqrt(sum_sq / static_cast<double>(points_L.size()));
}

void ModelDeviation::add(const std::vector<Vec3>& points_L, const SE3& correction, const SE3& motion) {
  if (rms_displacement_m(points_L, motion) < kMinMotion_m) return;
  const double deviation_m = rms_displacement_m(points_L, correction);
  sum_sq_m2_ += deviation_m * deviation_m;
  ++count_;
}

double ModelDeviation::sigma_m() const { return count_ > 0 ? std::sqrt(sum_sq_m2_ / count_) : 0.0; }

}  // namespace vilslam::lidar
