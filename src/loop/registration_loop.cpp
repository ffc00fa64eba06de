#include "loop/registration_loop.h"

#include "loop/constraint_fusion.h"
#include "loop/pose_graph.h"

namespace vilslam::loop {

std::optional<RegistrationLoop> registration_loop(const std::vector<KeyFrame>& map_key_frames,
                                                  const Trajectory& map_poses, const SE3& T_W_Lv,
                                                  const Mat6& information_Lv,
                                                  const std::vector<Vec6>& degenerate_directions,
                                                  double max_distance_m, const RegistrationLoopSigmas& sigmas) {
  std::optional<std::size_t> nearest;
  double nearest_m = max_distance_m;
  for (const KeyFrame& kf : map_key_frames) {
    const double d_m = (map_poses.at(kf.pose_index).T_W_B.translation() - T_W_Lv.translation()).norm();
    if (d_m <= nearest_m) nearest_m = d_m, nearest = kf.pose_index;
  }
  if (!nearest) return std::nullopt;
  Mat6 degenerate = Mat6::Zero();  // the projection onto the degenerate directions (orthonormal eigenvectors)
  for (const Vec6& v : degenerate_directions) degenerate += v.normalized() * v.normalized().transpose();
  const Mat6 keep = Mat6::Identity() - degenerate;
  const Mat6 measured = keep * information_Lv * keep / (sigmas.point_m * sigmas.point_m) +
                        degenerate * information_from_sigmas(sigmas.degenerate_m, sigmas.degenerate_rad) * degenerate;
  const SE3& T_W_Lu = map_poses[*nearest].T_W_B;
  return RegistrationLoop{*nearest, T_W_Lu.inverse() * T_W_Lv,
                          information_with_floor(measured, information_from_sigmas(sigmas.loop_m, sigmas.loop_rad))};
}

}  // namespace vilslam::loop
