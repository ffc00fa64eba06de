// `vilslam pose-graph --poses lidar.tum --loops loops.csv --out corrected.tum`: the global pose graph of
// LiDAR poses (odometry chain from the trajectory plus loop constraints), optimized and written as TUM
// (docs/pose_graph.md; loops.csv in docs/formats.md).
#include <cstdio>
#include <memory>
#include <string>

#include "io/trajectory_io.h"
#include "loop/loop_constraints_io.h"
#include "loop/pose_graph.h"
#include "vilslam/command.h"

namespace {

using namespace vilslam;

struct Options {
  std::string poses_path, loops_path, out_path;
  double odometry_sigma_m = 0.02;
  double odometry_sigma_rad = 0.002;
  loop::LoopSigmas loop_sigmas;
  std::string loss = "huber";
  double loss_scale = 1.0;
};

loop::RobustLoss parse_loss(const std::string& name) {
  if (name == "huber") return loop::RobustLoss::kHuber;
  if (name == "cauchy") return loop::RobustLoss::kCauchy;
  return loop::RobustLoss::kNone;
}

void print_stats(const char* label, const loop::ResidualStats& s) {
  std::printf("%-9s %5zu factors  whitened rms %.4f max %.4f  max error %.4f m %.6f rad\n", label, s.count,
              s.whitened_rms, s.whitened_max, s.translation_max_m, s.rotation_max_rad);
}

vilslam::cli::Command reg("pose-graph", "Optimize a LiDAR trajectory with loop constraints (global pose graph)",
                          [](CLI::App& app) {
  auto o = std::make_shared<Options>();
  app.add_option("--poses", o->poses_path, "LiDAR trajectory T_W_L (TUM)")->required();
  app.add_option("--loops", o->loops_path, "Loop constraints csv (docs/formats.md)")->required();
  app.add_option("--out", o->out_path, "Corrected trajectory (TUM)")->required();
  app.add_option("--odometry-sigma-m", o->odometry_sigma_m, "Odometry translation sigma, m")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  app.add_option("--odometry-sigma-rad", o->odometry_sigma_rad, "Odometry rotation sigma, rad")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  app.add_option("--loop-sigma-m", o->loop_sigmas.sigma_m, "Loop translation sigma of rows without one, m")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  app.add_option("--loop-sigma-rad", o->loop_sigmas.sigma_rad, "Loop rotation sigma of rows without one, rad")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  app.add_option("--loss", o->loss, "Robust loss of the loop factors")
      ->check(CLI::IsMember({"cauchy", "huber", "none"}))
      ->capture_default_str();
  app.add_option("--loss-scale", o->loss_scale, "Robust loss scale, in sigmas")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  return [o]() {
    const Trajectory poses = read_trajectory(o->poses_path, TrajectoryFormat::kTum);
    const auto loops = loop::read_loop_constraints(o->loops_path, poses, o->loop_sigmas);
    loop::PoseGraph graph;
    for (const TimedPose& p : poses) graph.add_pose(p.t_ns, p.T_W_B);
    const Mat6 odometry_information = loop::information_from_sigmas(o->odometry_sigma_m, o->odometry_sigma_rad);
    for (const auto& c : loop::odometry_constraints(poses, odometry_information)) graph.add_constraint(c);
    for (const auto& c : loops) graph.add_constraint(c);
    loop::PoseGraphOptions options;
    options.loop_loss = parse_loss(o->loss);
    options.loop_loss_scale = o->loss_scale;
    const loop::PoseGraphSummary summary = graph.optimize(options);
    std::printf("poses %zu, loops %zu, %d iterations, cost %.6g -> %.6g (%s)\n", poses.size(), loops.size(),
                summary.iterations, summary.initial_cost, summary.final_cost,
                summary.converged ? "converged" : "not converged");
    print_stats("odometry", summary.odometry);
    print_stats("loop", summary.loop);
    write_trajectory(o->out_path, graph.poses(), TrajectoryFormat::kTum);
    return 0;
  };
});

}  // namespace
