#include "eval/loop_eval.h"

#include <cmath>
#include <stdexcept>

#include "common/json_writer.h"
#include "eval/stats.h"

namespace vilslam::eval {
namespace {

constexpr double kRadToDeg = 180.0 / M_PI;

// Translation and rotation of T_true^-1 T_est.
std::pair<double, double> error_of(const SE3& T_est, const SE3& T_true) {
  const SE3 E = T_true.inverse() * T_est;
  return {E.translation().norm(), Eigen::AngleAxisd(E.quat()).angle() * kRadToDeg};
}

double median_or_zero(const std::vector<double>& v) { return v.empty() ? 0.0 : compute_stats(v).median; }

}  // namespace

LoopEvaluation evaluate_loops(const std::vector<LoopToEvaluate>& loops, const Trajectory& gt_T_W_L,
                              const LoopErrorCriteria& criteria) {
  if (gt_T_W_L.size() < 2) throw std::invalid_argument("ground truth has fewer than 2 poses");
  const auto covered = [&](TimeNs t) { return t >= gt_T_W_L.front().t_ns && t <= gt_T_W_L.back().t_ns; };
  LoopEvaluation e;
  std::vector<double> t_m, r_deg, epnp_t_m, epnp_r_deg;
  for (const LoopToEvaluate& loop : loops) {
    if (!covered(loop.from_t_ns) || !covered(loop.to_t_ns)) {
      throw std::invalid_argument("loop " + std::to_string(loop.from_t_ns) + " -> " + std::to_string(loop.to_t_ns) +
                                  " lies outside the ground truth's time span");
    }
    const SE3 T_true = pose_at(gt_T_W_L, loop.from_t_ns).inverse() * pose_at(gt_T_W_L, loop.to_t_ns);
    LoopError err;
    std::tie(err.translation_m, err.rotation_deg) = error_of(loop.T_from_to, T_true);
    if (loop.T_from_to_epnp) {
      const auto [t, r] = error_of(*loop.T_from_to_epnp, T_true);
      err.epnp_translation_m = t;
      err.epnp_rotation_deg = r;
      epnp_t_m.push_back(t);
      epnp_r_deg.push_back(r);
    }
    err.is_false = err.translation_m > criteria.false_translation_m || err.rotation_deg > criteria.false_rotation_deg;
    (err.is_false ? e.false_loops : e.true_loops) += 1;
    t_m.push_back(err.translation_m);
    r_deg.push_back(err.rotation_deg);
    e.loops.push_back(err);
  }
  e.median_translation_m = median_or_zero(t_m);
  e.median_rotation_deg = median_or_zero(r_deg);
  e.median_epnp_translation_m = median_or_zero(epnp_t_m);
  e.median_epnp_rotation_deg = median_or_zero(epnp_r_deg);
  return e;
}

std::string loop_evaluation_json(const LoopEvaluation& e, const std::vector<LoopToEvaluate>& loops) {
  JsonWriter json;
  json.begin_object();
  json.key("loops").value(static_cast<std::uint64_t>(e.loops.size()));
  json.key("true_loops").value(e.true_loops);
  json.key("false_loops").value(e.false_loops);
  json.key("median_translation_m").value(e.median_translation_m);
  json.key("median_rotation_deg").value(e.median_rotation_deg);
  json.key("median_epnp_translation_m").value(e.median_epnp_translation_m);
  json.key("median_epnp_rotation_deg").value(e.median_epnp_rotation_deg);
  json.key("per_loop").begin_array();
  for (std::size_t i = 0; i < e.loops.size(); ++i) {
    const LoopError& l = e.loops[i];
    json.begin_object();
    json.key("from_t_ns").value(static_cast<std::int64_t>(loops[i].from_t_ns));
    json.key("to_t_ns").value(static_cast<std::int64_t>(loops[i].to_t_ns));
    json.key("translation_m").value(l.translation_m);
    json.key("rotation_deg").value(l.rotation_deg);
    if (l.epnp_translation_m) json.key("epnp_translation_m").value(*l.epnp_translation_m);
    if (l.epnp_rotation_deg) json.key("epnp_rotation_deg").value(*l.epnp_rotation_deg);
    json.key("false").value(l.is_false);
    json.end_object();
  }
  json.end_array();
  json.end_object();
  return json.str();
}

}  // namespace vilslam::eval
