// Speed of the evaluation on the shared real data: the full trajectory evaluation of KITTI 00 and the
// map registration error of a real LiDAR scan against itself after an offset (ICP + per-point errors).
#include <benchmark/benchmark.h>

#include <filesystem>

#include "eval/map_error.h"
#include "eval/trajectory_eval.h"
#include "io/trajectory_io.h"

namespace {

using namespace vilslam;

std::string shared(const std::string& relative) { return std::string(VILSLAM_SHARED_DATA) + "/" + relative; }

void BM_EvaluateKitti00(benchmark::State& state) {
  if (!std::filesystem::exists(shared("trajectories/KITTI_00_gt.txt"))) {
    state.SkipWithError("shared data absent");
    return;
  }
  const Trajectory gt = read_trajectory(shared("trajectories/KITTI_00_gt.txt"), TrajectoryFormat::kKitti);
  const Trajectory est = read_trajectory(shared("trajectories/KITTI_00_ORB.txt"), TrajectoryFormat::kKitti);
  eval::TrajectoryEvalConfig config;
  config.rpe = {10.0, eval::DeltaUnit::kMeters};
  for (auto _ : state) benchmark::DoNotOptimize(eval::evaluate_trajectory(est, gt, config));
}
BENCHMARK(BM_EvaluateKitti00)->Unit(benchmark::kMillisecond);

void BM_MapErrorRealScan(benchmark::State& state) {
  if (!std::filesystem::exists(shared("lidar/small_gicp/target.ply"))) {
    state.SkipWithError("shared data absent");
    return;
  }
  const PointCloud model = read_cloud(shared("lidar/small_gicp/target.ply"));
  const SE3 offset(so3::exp_quat(Vec3(0.01, -0.02, 0.05)), Vec3(0.3, -0.2, 0.1));
  PointCloud map;
  for (const auto& p : model.points) map.points.push_back((offset * p.cast<double>()).cast<float>());
  eval::MapErrorConfig config;
  config.icp.mode = state.range(0) ? eval::IcpMode::kPointToPlane : eval::IcpMode::kPointToPoint;
  for (auto _ : state) benchmark::DoNotOptimize(eval::compute_map_error(map, model, config));
  state.SetLabel(state.range(0) ? "point_to_plane" : "point_to_point");
}
BENCHMARK(BM_MapErrorRealScan)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

}  // namespace
