#include "eval/map_error.h"

#include <cmath>
#include <cstdio>
#include <stdexcept>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "common/point_index.h"
#include "eval/stats.h"

namespace vilslam::eval {
namespace {

// Every k-th point, k = ceil(n / max_points): a deterministic, evenly spread subsample.
std::vector<Eigen::Vector3f> strided_subsample(const std::vector<Eigen::Vector3f>& points, std::size_t max_points) {
  if (max_points == 0 || points.size() <= max_points) return points;
  const std::size_t stride = (points.size() + max_points - 1) / max_points;
  std::vector<Eigen::Vector3f> out;
  out.reserve(points.size() / stride + 1);
  for (std::size_t i = 0; i < points.size(); i += stride) out.push_back(points[i]);
  return out;
}

}  // namespace

MapError compute_map_error(const PointCloud& map, const PointCloud& model, const MapErrorConfig& config) {
  return compute_map_error(map, map, model, config);
}

MapError compute_map_error(const PointCloud& map, const PointCloud& align_map, const PointCloud& model,
                           const MapErrorConfig& config) {
  if (map.points.empty() || align_map.points.empty() || model.points.empty())
    throw std::invalid_argument("map error needs non-empty clouds");
  const PointIndex index(model.points);
  MapError out;
  out.icp.T_model_map = config.initial.T_model_map;
  if (config.align) {
    const bool to_plane = config.icp.mode == IcpMode::kPointToPlane;
    const auto normals = to_plane ? estimate_normals(index, config.icp.normal_neighbours) : std::vector<Eigen::Vector3f>{};
    out.icp = align_icp(strided_subsample(align_map.points, config.max_icp_points), index, normals, config.icp,
                        config.initial.T_model_map);
  }
  out.per_point_m.resize(map.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, map.size(), 1024), [&](const auto& range) {
    for (std::size_t i = range.begin(); i != range.end(); ++i) {
      const Eigen::Vector3f p = (out.icp.T_model_map * map.points[i].cast<double>()).cast<float>();
      out.per_point_m[i] = std::sqrt(index.nearest(p).dist_sq);
    }
  });
  const std::vector<double> errors(out.per_point_m.begin(), out.per_point_m.end());
  const ErrorStats stats = compute_stats(errors);
  out.mean_m = stats.mean;
  out.median_m = stats.median;
  out.p95_m = percentile(errors, 95.0);
  return out;
}

InitialAlignment first_pose_alignment(const Trajectory& est, const Trajectory& gt) {
  if (est.empty()) throw std::invalid_argument("no estimated poses");
  if (gt.size() < 2) throw std::invalid_argument("ground truth has fewer than 2 poses");
  const TimeNs t0_ns = est.front().t_ns;
  if (t0_ns < gt.front().t_ns || t0_ns > gt.back().t_ns) {
    char buf[160];
    std::snprintf(buf, sizeof buf, "first pose at %.9f s lies outside the ground truth's span (%.9f s to %.9f s)",
                  ns_to_s(t0_ns), ns_to_s(gt.front().t_ns), ns_to_s(gt.back().t_ns));
    throw std::invalid_argument(buf);
  }
  return {pose_at(gt, t0_ns) * est.front().T_W_B.inverse(), t0_ns};
}

}  // namespace vilslam::eval
