// `vilslam eval --est FILE --gt FILE ...`: APE, RPE, the KITTI segment metric and the final drift of an
// estimated trajectory against ground truth (docs/evaluation.md).
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>

#include "common/error.h"
#include "common/json_writer.h"
#include "eval/alignment.h"
#include "eval/association.h"
#include "eval/eval_json.h"
#include "eval/trajectory_eval.h"
#include "io/dataset_groundtruth.h"
#include "io/trajectory_io.h"
#include "vilslam/command.h"

namespace {

using namespace vilslam;

struct Options {
  std::string est_path, gt_path, json_path;
  std::string format, est_format, gt_format;
  std::string times, est_times, gt_times;
  std::string align = "se3";
  std::size_t align_first_n = 0;
  double delta = 1.0;
  std::string delta_unit = "frames";
  double max_diff_s = 0.01;
  std::string gt_frame = "imu";
  std::string map_dir;
  std::string map_gt_path;
  bool tilt = false;
  std::optional<double> start_s, end_s;  // window of the estimate, seconds after its first pose
};

Trajectory load(const std::string& path, const std::string& format, const std::string& fallback_format,
                const std::string& times) {
  const std::string name = !format.empty() ? format : fallback_format;
  const TrajectoryFormat f = name.empty() ? detect_trajectory_format(path) : parse_trajectory_format(name);
  return read_trajectory(path, f, times);
}

void print_stats_row(const char* label, const eval::ErrorStats& s, const std::string& note = {}) {
  std::printf("%-16s %10.5f %10.5f %10.5f %10.5f %10.5f %10.5f %7zu%s\n", label, s.rmse, s.mean, s.median, s.std, s.min,
              s.max, s.count, note.c_str());
}

// A run that lost track leaves part of the reference unmatched: its ATE is over the rest only, and says so.
constexpr double kMinFullCoverage = 0.95;

std::string coverage_note(double coverage) {
  char note[96];
  std::snprintf(note, sizeof note, "   over %.1f %% of the reference%s", 100.0 * coverage,
                coverage < kMinFullCoverage ? " (less than 95 %: part of the run only)" : "");
  return note;
}

void print(const eval::TrajectoryEvalReport& r, const Options& o) {
  std::printf("reference coverage: %.4f\n", r.reference_coverage);
  std::printf("matched poses: %zu\nalignment: %s (scale %.6f, first %s poses)\n", r.matched_poses,
              eval::align_mode_name(r.alignment.mode).c_str(), r.alignment.scale,
              o.align_first_n == 0 ? "all" : std::to_string(o.align_first_n).c_str());
  std::printf("path length: %.3f m\nFDE: %.4f %% (%.4f m)   start-aligned vs gt: %.4f %% (%.4f m)\n", r.path_length_m,
              r.fde.percent, r.fde.drift_m, r.fde_start_aligned.percent, r.fde_start_aligned.drift_m);
  if (r.kitti.segments > 0) {
    std::printf("KITTI: t_err %.4f %%  r_err %.6f deg/m  (%zu segments)\n", r.kitti.t_err_percent,
                r.kitti.r_err_deg_per_m, r.kitti.segments);
  } else {
    std::printf("KITTI: no segment (ground-truth path shorter than 100 m)\n");
  }
  std::printf("RPE: delta %g %s, consecutive pairs\n", o.delta, o.delta_unit.c_str());
  std::printf("%-16s %10s %10s %10s %10s %10s %10s %7s\n", "metric", "rmse", "mean", "median", "std", "min", "max", "n");
  print_stats_row("APE [m]", r.ape.trans, coverage_note(r.reference_coverage));
  print_stats_row("APE rot [deg]", r.ape.rot);
  print_stats_row("RPE [m]", r.rpe.trans);
  print_stats_row("RPE rot [deg]", r.rpe.rot);
  if (r.tilt_deg.count > 0) print_stats_row("tilt [deg]", r.tilt_deg);
}

// The estimate's poses in [start, end) seconds after its first pose (open ends stay open).
Trajectory in_window(const Trajectory& est, const Options& o) {
  if (est.empty() || (!o.start_s && !o.end_s)) return est;
  for (const auto& [name, value] : {std::pair{"--start-s", o.start_s}, std::pair{"--end-s", o.end_s}})
    if (value && !std::isfinite(*value)) throw std::invalid_argument(std::string(name) + " must be finite");
  const TimeNs t0 = est.front().t_ns;
  Trajectory out;
  for (const TimedPose& p : est) {
    if (o.start_s && p.t_ns < t0 + s_to_ns(*o.start_s)) continue;
    if (o.end_s && p.t_ns >= t0 + s_to_ns(*o.end_s)) continue;
    out.push_back(p);
  }
  return out;
}

Trajectory groundtruth(const Options& o, const std::string& path) {
  return std::filesystem::is_directory(path)
             ? dataset_groundtruth(path, o.gt_frame == "lidar" ? GroundTruthFrame::kLidar : GroundTruthFrame::kImu)
             : load(path, o.gt_format, o.format, o.gt_times.empty() ? o.times : o.gt_times);
}

// --map: the ground truth moved into a saved map's frame by one SE(3) fit of the map's own poses to their
// ground truth (the map is fitted, never the estimate). Throws InputError when they do not overlap.
Trajectory in_map_frame(const Trajectory& gt, const Options& o) {
  const std::string poses_path = (std::filesystem::path(o.map_dir) / "poses.tum").string();
  const Trajectory map_poses = read_trajectory(poses_path, TrajectoryFormat::kTum);
  const Trajectory map_gt = groundtruth(o, o.map_gt_path);
  const eval::Association a = eval::associate(map_poses, map_gt);
  if (a.size() < 3) throw InputError(poses_path, "fewer than 3 poses matched in time with " + o.map_gt_path);
  // align_trajectories(est, gt) fits p_gt ~ T p_est: here est = the map's ground truth, gt = the map's poses.
  const eval::Alignment T_map_W = eval::align_trajectories(eval::select(map_gt, a.gt_ids),
                                                           eval::select(map_poses, a.est_ids), eval::AlignMode::kSe3);
  return eval::apply_alignment(gt, T_map_W);
}

vilslam::cli::Command reg("eval", "Trajectory errors (APE, RPE, KITTI, final drift) against ground truth",
                          [](CLI::App& app) {
  auto o = std::make_shared<Options>();
  const auto formats = CLI::IsMember({"tum", "kitti", "euroc"});
  app.add_option("--est", o->est_path, "Estimated trajectory")->required();
  app.add_option("--gt", o->gt_path, "Ground-truth trajectory, or a dataset folder (its ground truth in --gt-frame)")
      ->required();
  app.add_option("--gt-frame", o->gt_frame, "With a dataset folder as --gt: the body of its ground truth")
      ->check(CLI::IsMember({"imu", "lidar"}))
      ->capture_default_str();
  app.add_option("--format", o->format, "Format of both files (default: detected)")->check(formats);
  app.add_option("--est-format", o->est_format, "Format of the estimate")->check(formats);
  app.add_option("--gt-format", o->gt_format, "Format of the ground truth")->check(formats);
  app.add_option("--times", o->times, "KITTI times file for both (default: pose index in seconds)");
  app.add_option("--est-times", o->est_times, "KITTI times file of the estimate");
  app.add_option("--gt-times", o->gt_times, "KITTI times file of the ground truth");
  app.add_option("--align", o->align, "Alignment before APE")
      ->check(CLI::IsMember({"se3", "sim3", "posyaw", "none"}))
      ->capture_default_str();
  app.add_option("--align-first", o->align_first_n, "Align on the first N matched poses (0 = all)")->capture_default_str();
  app.add_option("--delta", o->delta, "RPE pose-pair distance")->check(CLI::PositiveNumber)->capture_default_str();
  app.add_option("--delta-unit", o->delta_unit, "RPE delta unit")
      ->check(CLI::IsMember({"m", "frames"}))
      ->capture_default_str();
  app.add_option("--max-diff", o->max_diff_s, "Largest time difference of associated poses, s")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  app.add_option("--json", o->json_path, "Also write the results as JSON to this file");
  app.add_flag("--tilt", o->tilt,
               "Also the tilt error: the angle between the estimate's and the ground truth's up directions in the "
               "body, unaligned (both frames z up and gravity-aligned)");
  app.add_option("--start-s", o->start_s, "Only the estimate's poses at or after this many seconds after its first");
  app.add_option("--end-s", o->end_s, "Only the estimate's poses before this many seconds after its first");
  auto* map_gt = app.add_option("--map-gt", o->map_gt_path, "The --map's ground truth (file, or dataset folder in --gt-frame)");
  app.add_option("--map", o->map_dir,
                 "A saved map (run --save-map) whose frame the estimate is in (run --load-map): the ground truth is "
                 "moved there by one SE(3) fit of the map's poses to --map-gt; use with --align none")
      ->needs(map_gt);
  map_gt->needs("--map");
  return [o]() {
    const Trajectory est =
        in_window(load(o->est_path, o->est_format, o->format, o->est_times.empty() ? o->times : o->est_times), *o);
    const Trajectory gt = o->map_dir.empty() ? groundtruth(*o, o->gt_path) : in_map_frame(groundtruth(*o, o->gt_path), *o);
    eval::TrajectoryEvalConfig config;
    config.align = eval::parse_align_mode(o->align);
    config.align_first_n = o->align_first_n;
    config.rpe = {o->delta, o->delta_unit == "m" ? eval::DeltaUnit::kMeters : eval::DeltaUnit::kFrames};
    config.max_diff_ns = s_to_ns(o->max_diff_s);
    config.tilt = o->tilt;
    eval::TrajectoryEvalReport report;
    try {
      report = eval::evaluate_trajectory(est, gt, config);
    } catch (const std::invalid_argument& e) {
      throw InputError(o->est_path, std::string("cannot evaluate against ") + o->gt_path + ": " + e.what());
    }
    print(report, *o);
    if (!o->json_path.empty()) write_file_atomic(o->json_path, eval::trajectory_report_json(report, config));
    return 0;
  };
});

}  // namespace
