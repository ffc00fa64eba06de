#include "eval/tilt_error.h"

#include <cmath>
#include <stdexcept>

namespace vilslam::eval {

std::vector<double> tilt_errors_deg(const Trajectory& gt, const Trajectory& est) {
  if (gt.size() != est.size() || gt.empty()) throw std::invalid_argument("tilt error needs matched, non-empty poses");
  std::vector<double> out;
  out.reserve(gt.size());
  for (std::size_t i = 0; i < gt.size(); ++i) {
    // The world's e_z in each body frame: the third row of R_W_B.
    const Vec3 up_est = est[i].T_W_B.rotation().row(2).transpose();
    const Vec3 up_gt = gt[i].T_W_B.rotation().row(2).transpose();
    // atan2 of |a x b| and a . b keeps the small angles exact (acos loses them near 1).
    out.push_back(std::atan2(up_est.cross(up_gt).norm(), up_est.dot(up_gt)) * 180.0 / M_PI);
  }
  return out;
}

}  // namespace vilslam::eval
