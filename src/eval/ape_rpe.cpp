#include "eval/ape_rpe.h"

#include <cmath>
#include <stdexcept>

namespace vilslam::eval {
namespace {

double angle_deg(const Quat& q) { return so3::log(q).norm() * 180.0 / M_PI; }

void check_matched(const Trajectory& gt, const Trajectory& est) {
  if (gt.size() != est.size()) throw std::invalid_argument("pose errors need matched trajectories");
  if (gt.empty()) throw std::invalid_argument("pose errors need at least one pose");
}

void finish(PoseErrors& e) {
  e.trans = compute_stats(e.trans_m);
  e.rot = compute_stats(e.rot_deg);
}

}  // namespace

PoseErrors compute_ape(const Trajectory& gt, const Trajectory& est) {
  check_matched(gt, est);
  PoseErrors e;
  for (std::size_t i = 0; i < gt.size(); ++i) {
    e.trans_m.push_back((est[i].T_W_B.translation() - gt[i].T_W_B.translation()).norm());
    e.rot_deg.push_back(angle_deg(est[i].T_W_B.quat().conjugate() * gt[i].T_W_B.quat()));
  }
  finish(e);
  return e;
}

std::vector<std::pair<std::size_t, std::size_t>> rpe_pairs(const Trajectory& poses, const RpeConfig& config) {
  if (!(config.delta > 0)) throw std::invalid_argument("RPE delta must be positive");
  std::vector<std::size_t> ids;
  if (config.unit == DeltaUnit::kFrames) {
    if (config.delta != std::floor(config.delta)) throw std::invalid_argument("RPE delta in frames must be an integer");
    const auto step = static_cast<std::size_t>(config.delta);
    for (std::size_t i = 0; i < poses.size(); i += step) ids.push_back(i);
  } else {
    double path_m = 0;
    for (std::size_t i = 1; i < poses.size(); ++i) {
      path_m += (poses[i].T_W_B.translation() - poses[i - 1].T_W_B.translation()).norm();
      if (path_m >= config.delta) {
        ids.push_back(i);
        path_m = 0;
      }
    }
  }
  std::vector<std::pair<std::size_t, std::size_t>> pairs;
  for (std::size_t k = 1; k < ids.size(); ++k) pairs.emplace_back(ids[k - 1], ids[k]);
  return pairs;
}

PoseErrors compute_rpe(const Trajectory& gt, const Trajectory& est, const RpeConfig& config) {
  check_matched(gt, est);
  const auto pairs = rpe_pairs(est, config);
  if (pairs.empty()) throw std::invalid_argument("RPE delta produced no pose pair");
  PoseErrors e;
  for (const auto& [i, j] : pairs) {
    const SE3 gt_rel = gt[i].T_W_B.inverse() * gt[j].T_W_B;
    const SE3 est_rel = est[i].T_W_B.inverse() * est[j].T_W_B;
    const SE3 error = gt_rel.inverse() * est_rel;
    e.trans_m.push_back(error.translation().norm());
    e.rot_deg.push_back(angle_deg(error.quat()));
  }
  finish(e);
  return e;
}

}  // namespace vilslam::eval
