// `vilslam eval-loops --loops loops.csv --gt GT`: each accepted loop's constraint against the true relative
// pose, true and false loops (docs/evaluation.md).
#include <cstdio>
#include <memory>
#include <stdexcept>
#include <string>

#include "common/error.h"
#include "common/json_writer.h"
#include "eval/loop_eval.h"
#include "io/dataset_groundtruth.h"
#include "loop/loop_constraints_io.h"
#include "vilslam/command.h"

namespace {

using namespace vilslam;

struct Options {
  std::string loops_path, gt_path, json_path;
};

vilslam::cli::Command reg("eval-loops", "Errors of loop constraints (loops.csv) against ground truth, true and false loops",
                          [](CLI::App& app) {
  auto o = std::make_shared<Options>();
  app.add_option("--loops", o->loops_path, "loops.csv of a run")->required();
  app.add_option("--gt", o->gt_path, "Ground truth: a dataset folder, or a TUM file of LiDAR poses T_W_L")->required();
  app.add_option("--json", o->json_path, "Also write the results as JSON to this file");
  return [o]() {
    std::vector<eval::LoopToEvaluate> loops;
    for (const loop::LoopRow& row : loop::read_loop_rows(o->loops_path)) {
      loops.push_back({row.from_t_ns, row.to_t_ns, row.T_from_to, row.T_from_to_epnp});
    }
    const Trajectory gt = read_groundtruth(o->gt_path, GroundTruthFrame::kLidar);
    eval::LoopEvaluation e;
    try {
      e = eval::evaluate_loops(loops, gt);
    } catch (const std::invalid_argument& err) {
      throw InputError(o->loops_path, std::string("cannot evaluate against ") + o->gt_path + ": " + err.what());
    }
    std::printf("%-20s %-20s %10s %9s %10s %9s %s\n", "from_t_ns", "to_t_ns", "err_m", "err_deg", "epnp_m",
                "epnp_deg", "verdict");
    for (std::size_t i = 0; i < loops.size(); ++i) {
      const eval::LoopError& l = e.loops[i];
      std::printf("%-20lld %-20lld %10.4f %9.4f %10.4f %9.4f %s\n", static_cast<long long>(loops[i].from_t_ns),
                  static_cast<long long>(loops[i].to_t_ns), l.translation_m, l.rotation_deg,
                  l.epnp_translation_m.value_or(NAN), l.epnp_rotation_deg.value_or(NAN), l.is_false ? "FALSE" : "true");
    }
    std::printf("loops %zu: true %d, false %d (false: error > 0.3 m or > 3 deg)\n", loops.size(), e.true_loops,
                e.false_loops);
    std::printf("median error: EPnP + ICP %.4f m / %.4f deg; EPnP alone %.4f m / %.4f deg\n", e.median_translation_m,
                e.median_rotation_deg, e.median_epnp_translation_m, e.median_epnp_rotation_deg);
    if (!o->json_path.empty()) write_file_atomic(o->json_path, eval::loop_evaluation_json(e, loops));
    return 0;
  };
});

}  // namespace
