#include "eval/odometry_markdown.h"

#include <cmath>
#include <cstdarg>
#include <cstdio>

namespace vilslam::eval {
namespace {

std::string format(const char* fmt, ...) {
  char buf[512];
  va_list args;
  va_start(args, fmt);
  std::vsnprintf(buf, sizeof buf, fmt, args);
  va_end(args);
  return buf;
}

// "0.292 % (0.342 m)", with a dagger when the drift is measured against ground truth (open route).
std::string fde_cell(const DriftResult& d, bool closed) {
  if (d.lost) return "**lost**";
  return format("%.3f %%%s (%.3f m)", d.fde_percent, closed ? "" : "†", d.drift_m);
}

// ATE RMSE after the run's own alignment (posyaw / se3) or after SE(3); "–" when there is none.
std::string ate_cell(const DriftResult& d, bool se3) {
  const double rmse_m = se3 ? d.ate_se3_rmse_m : d.ate_rmse_m;
  if ((d.lost && d.path_length_m == 0) || !std::isfinite(rmse_m)) return "–";
  return format("%.3f", rmse_m);
}

std::string paper_fde(const std::optional<double>& percent) {
  return percent ? format("%.2f %%", *percent) : std::string("not finished");
}

// The paper's FDE after loop closure, or what its text says instead.
std::string paper_loop_fde(const PaperOdometry& paper) {
  if (paper.vil_slam_loop_fde_percent) return format("%.2f %%", *paper.vil_slam_loop_fde_percent);
  return paper.loop_remark.empty() ? std::string("n/r") : paper.loop_remark;
}

// "examined / accepted / false" candidates of the VIL run's loop closure.
std::string loop_counts_cell(const std::optional<LoopClosureResult>& loops) {
  if (!loops) return "–";
  return format("%zu / %zu / %d", loops->candidates_examined, loops->accepted.loops.size(), loops->accepted.false_loops);
}

// Median error of the accepted loops' constraints, EPnP + ICP / EPnP alone; "–" without accepted loops.
std::string loop_error_cell(const std::optional<LoopClosureResult>& loops) {
  if (!loops || loops->accepted.loops.empty()) return "–";
  const LoopEvaluation& e = loops->accepted;
  return format("%.3f m %.2f° / %.3f m %.2f°", e.median_translation_m, e.median_rotation_deg, e.median_epnp_translation_m,
                e.median_epnp_rotation_deg);
}

// Whether the VIL FDE reaches the paper's VIL-SLAM odometry FDE.
std::string meets_paper(const OdometryRow& row, const std::optional<PaperOdometry>& paper) {
  if (!paper) return "–";
  if (row.vil.lost) return "no (lost)";
  return row.vil.fde_percent <= paper->vil_slam_fde_percent ? "yes" : "no";
}

// Mean MRE in m, "*" when ICP did not converge, "–" without a map.
std::string mre_cell(const MapRegistration& m) {
  if (!m.failure.empty()) return "–";
  return format("%.3f%s", m.mean_m, m.icp_converged ? "" : "*");
}

// "VIL / VIL + loop / LiDAR-only / true poses" MRE.
std::string maps_cell(const std::optional<MapErrors>& maps) {
  if (!maps) return "not measured";
  return mre_cell(maps->vil) + " / " + mre_cell(maps->vil_final) + " / " + mre_cell(maps->lidar_only) + " / " +
         mre_cell(maps->truth);
}

std::string paper_mre(const std::optional<double>& m) { return m ? format("%.2f", *m) : std::string("×"); }

// Whether the loop-corrected map's MRE reaches the paper's VIL-SLAM MRE.
std::string meets_paper_mre(const OdometryRow& row, const std::optional<PaperOdometry>& paper) {
  if (!paper || !paper->vil_slam_mre_m || !row.maps) return "–";
  const MapRegistration& m = row.maps->vil_final;
  if (!m.failure.empty()) return "no (no map)";
  return m.mean_m <= *paper->vil_slam_mre_m ? "yes" : "no";
}

void append_map_failure(std::string& out, const OdometryRow& row, const char* name, const MapRegistration& m) {
  if (!m.failure.empty()) out += format("- %s, %s: %s\n", row.preset.c_str(), name, m.failure.c_str());
}

void append_lost(std::string& out, const OdometryRow& row, const char* name, const DriftResult& d) {
  if (!d.lost) return;
  out += format("- %s, %s: lost, %s", row.preset.c_str(), name, d.lost_reason.c_str());
  if (d.poses >= 2 && d.path_length_m > 0)
    out += format(" (%zu poses; FDE %.3f %%, %.3f m; ATE RMSE %.3f m)", d.poses, d.fde_percent, d.drift_m, d.ate_rmse_m);
  out += "\n";
}

// The voxel size of the dense maps and the time they took, or why there are none.
std::string maps_note(const std::vector<OdometryRow>& rows) {
  double voxel_m = 0, wall_s = 0;
  int maps = 0;
  for (const OdometryRow& row : rows) {
    if (!row.maps) continue;
    voxel_m = row.maps->voxel_m;
    for (const MapRegistration* m : {&row.maps->vil, &row.maps->vil_final, &row.maps->lidar_only, &row.maps->truth}) {
      wall_s += m->wall_s;
      maps += m->failure.empty() ? 1 : 0;
    }
  }
  if (voxel_m == 0) return "The dense maps were not measured (`--no-maps`).\n\n";
  return format("Dense maps in voxels of %.3f m (`--map-voxel`; `vilslam map` defaults to the paper's 1 cm, which\n"
                "costs minutes and gigabytes per map of a full preset, and the MRE depends on the voxel size:\n"
                "docs/evaluation.md compares 1, 2 and 5 cm on one run). Building and measuring the %d maps took %.1f min.\n\n",
                voxel_m, maps, wall_s / 60);
}

}  // namespace

std::string odometry_table_markdown(const std::vector<OdometryRow>& rows) {
  std::string out =
      "| preset | simulation | length (m) | GT end-start gap (m) | VIO FDE | VIL FDE | LiDAR-only FDE | VIL + loop FDE | "
      "paper VIL-SLAM | paper LOAM | paper VIO | paper VIL-SLAM + loop | VIL <= paper | "
      "degenerate sweeps VIL / LiDAR-only | ATE RMSE VIO / VIL / LiDAR-only (m) | ATE RMSE se3 VIO / VIL / VIL + loop (m) | "
      "loops examined / accepted / false | median loop error EPnP+ICP / EPnP | "
      "MRE VIL / VIL + loop / LiDAR-only / true poses (m) | paper MRE VIL-SLAM / LOAM (m) | VIL + loop MRE <= paper |\n"
      "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const OdometryRow& row : rows) {
    const std::optional<PaperOdometry> paper = paper_odometry(row.preset);
    out += format("| %s | %s | %.1f | %.3f | %s | %s | %s | %s | ", row.preset.c_str(), row.source.c_str(),
                  row.gt_length_m, row.gt_gap_m, fde_cell(row.vio, row.closed).c_str(),
                  fde_cell(row.vil, row.closed).c_str(), fde_cell(row.lidar_only, row.closed).c_str(),
                  fde_cell(row.vil_final, row.closed).c_str());
    out += paper ? format("%.2f %% (%.0f m) | %s | n/r | %s | ", paper->vil_slam_fde_percent, paper->length_m,
                          paper_fde(paper->loam_fde_percent).c_str(), paper_loop_fde(*paper).c_str())
                 : std::string("– | – | – | – | ");
    out += format("%s | %zu of %zu / %zu of %zu | %s / %s / %s | %s / %s / %s | %s | %s | ",
                  meets_paper(row, paper).c_str(), row.vil_degenerate, row.vil_sweeps, row.lidar_only_degenerate,
                  row.lidar_only_sweeps, ate_cell(row.vio, false).c_str(), ate_cell(row.vil, false).c_str(),
                  ate_cell(row.lidar_only, false).c_str(), ate_cell(row.vio, true).c_str(), ate_cell(row.vil, true).c_str(),
                  ate_cell(row.vil_final, true).c_str(), loop_counts_cell(row.loops).c_str(),
                  loop_error_cell(row.loops).c_str());
    out += maps_cell(row.maps) + " | " +
           (paper ? paper_mre(paper->vil_slam_mre_m) + " / " + paper_mre(paper->loam_mre_m) : std::string("–")) + " | " +
           meets_paper_mre(row, paper) + " |\n";
  }
  std::string lost;
  for (const OdometryRow& row : rows) {
    append_lost(lost, row, "VIO", row.vio);
    append_lost(lost, row, "VIL", row.vil);
    append_lost(lost, row, "LiDAR-only", row.lidar_only);
    append_lost(lost, row, "VIL + loop", row.vil_final);
  }
  if (!lost.empty()) out += "\nLost runs:\n\n" + lost;
  std::string no_map;
  for (const OdometryRow& row : rows) {
    if (!row.maps) continue;
    append_map_failure(no_map, row, "VIL map", row.maps->vil);
    append_map_failure(no_map, row, "VIL + loop map", row.maps->vil_final);
    append_map_failure(no_map, row, "LiDAR-only map", row.maps->lidar_only);
    append_map_failure(no_map, row, "true-pose map", row.maps->truth);
  }
  if (!no_map.empty()) out += "\nDense maps without MRE:\n\n" + no_map;
  return out;
}

std::string odometry_document_markdown(const std::vector<OdometryRow>& rows, const OdometryDocument& doc) {
  std::string out =
      "# Table I on the simulated presets: VIO, VIL, LiDAR-only and loop-closed final drift, map registration error\n\n"
      "The paper's Table I (FDE and MRE) on the simulator's presets (docs/simulator.md): each\n"
      "dataset is run in `vil` mode (frontend + VIO, LiDAR mapping with the VIO's IMU-rate poses as motion prior,\n"
      "loop closure feeding its corrections back to the mapper) and in `lidar-only` mode (the mapper with a\n"
      "constant-velocity model, the paper's LOAM baseline), as `vilslam run` does (docs/pipeline.md). The VIO-only\n"
      "trajectory is the `vil` run's camera-rate states (`vio_camera.tum`): the LiDAR never feeds back into the VIO.\n\n"
      "Made by one command (`apps/vilslam/cmd_odometry_table.cpp`, `src/eval/odometry_table.h`):\n\n    " +
      doc.command +
      "\n\n"
      "It reuses `WORK/<preset>` when that folder already holds a complete simulation, else simulates it there\n"
      "(`vilslam simulate <preset> --seed S`), and writes the runs to `WORK/<preset>_vil` and\n"
      "`WORK/<preset>_lidar-only` (the files of `vilslam run`). `--config RUN_YAML` gives both runs that run\n"
      "config (as `vilslam run --config`); without it they use the built-in defaults.\n\n"
      "## Definitions\n\n"
      "- **FDE** (final drift error, the paper's odometry measure): the distance between the estimate's last and\n"
      "  first position over the estimate's path length, in %. It measures drift only when the route closes: the\n"
      "  column *GT end-start gap* is that distance for the ground truth (IMU and LiDAR frames, the larger); a\n"
      "  route closes when it is at most 0.01 m. On a route that does not close (marked †), the FDE is instead\n"
      "  the drift against ground truth: the estimate moved rigidly onto the first ground-truth pose, the distance\n"
      "  between its last position and the last ground-truth position, over the ground-truth path length.\n"
      "- **VIO**: camera-rate VIO states `T_W_I`; **VIL**, **VIL + loop** and **LiDAR-only**: LiDAR poses `T_W_L`,\n"
      "  one per sweep, compared with the ground truth moved into the LiDAR frame (`T_W_I T_I_L`). **VIL** is the\n"
      "  LiDAR odometry (`lidar.tum`: the mapper's relative motions composed, untouched by loop corrections);\n"
      "  **VIL + loop** is the loop-closed trajectory (`lidar_final.tum`: the final optimized global pose graph),\n"
      "  evaluated with the same rules as VIL.\n"
      "- **ATE RMSE**: APE translation RMSE after alignment (docs/evaluation.md): `posyaw` for VIO and VIL (the\n"
      "  VIO's world is gravity aligned, yaw and position are unobservable; VIL + loop too, for its lost rule),\n"
      "  `se3` for LiDAR-only (it starts in the first sweep's frame). The posyaw alignment keeps the roll and\n"
      "  pitch of the estimate's world (the VIO's gravity estimate at initialization, which the VIL map inherits);\n"
      "  the *se3* column aligns VIO, VIL and VIL + loop in SE(3), so its difference from the posyaw column shows\n"
      "  that tilt, and VIL beside VIL + loop shows what loop closure removed. On a route that returns to its start\n"
      "  a loop pulls the end onto the start, so a small FDE after loop closure alone does not show that the middle\n"
      "  of the route is right; the ATE does.\n"
      "- **Lost**: the run threw, gave fewer than 2 poses or a non-finite pose, spans less than 50 % of the\n"
      "  sequence, or after the ATE alignment some pose lies farther from ground truth than 10 % of the path\n"
      "  length (at least 1 m). A lost run's FDE is not tabulated; its reason and numbers are listed below the table.\n"
      "- **Loops** of the `vil` run: *examined*, the candidates the loop closer verified (docs/loop.md,\n"
      "  `loop_candidates.csv`); *accepted*, those that became loop factors (`loops.csv`); *false*, accepted loops\n"
      "  whose constraint `T_Lu_Lv` is more than 0.3 m or 3° from the ground-truth relative pose of the two LiDAR\n"
      "  poses (`eval/loop_eval.h`, as `vilslam eval-loops`). **Median loop error**: the median translation and\n"
      "  rotation error of the accepted loops' constraints against that ground truth, EPnP + ICP (the constraint)\n"
      "  / EPnP alone (before the ICP refinement); \"–\" when no loop was accepted.\n"
      "- **MRE** (map registration error, the paper's mapping measure): the mean distance of the dense map's points\n"
      "  to the nearest point of the reference model (`model.ply`, the simulator's sampling of every surface, the\n"
      "  paper's Faro scans). The map is aligned to the model by the first pose only, then ICP (docs/evaluation.md):\n"
      "  the alignment starts at `T_gt(t0) T_est(t0)^-1` at the trajectory's first pose and point-to-plane ICP refines\n"
      "  it; the whole ground truth is never used to align, so what the trajectory drifted stays in the map. The dense\n"
      "  map is that of `vilslam map` (every sweep dewarped and stitched with the LiDAR poses, docs/map.md) in voxels\n"
      "  of the size given below the table. Four maps per preset: VIL (`lidar.tum`), VIL + loop (`lidar_final.tum`),\n"
      "  LiDAR-only, and the ground-truth LiDAR poses, the floor no trajectory reaches below (range noise, voxel\n"
      "  size and the model's 0.05 m point spacing). `*`: ICP did not converge in 50 iterations. A lost run gets no map.\n"
      "- **Degenerate sweeps**: sweeps the mapper flagged degenerate (an eigenvalue of `J^T J` below its\n"
      "  threshold, docs/lidar.md), of the sweeps mapped.\n"
      "- **length**: the ground truth's path length.\n\n"
      "## Table\n\n" +
      odometry_table_markdown(rows) +
      "\n"
      "Paper values: VIL-SLAM paper Table I (\"FDE (%) and MRE (m) test results\"), odometry FDE of VIL-SLAM and\n"
      "of LOAM (laboshinl/loam_velodyne) on the real tests of the same names, with their path lengths;\n"
      "\"not finished\" is the paper's \"-\". *paper VIL-SLAM + loop* is not in Table I but in the text of its\n"
      "results section: loop closure lowered the hallway FDE to 0.05 % (two loops near the end point) and the\n"
      "tunnel FDE to 0.08 % (one loop about 3 m from the end point); on the highbay it \"closes the loop\" with no\n"
      "FDE given; on the huge loop the 0.01 % is odometry \"without loop closure being triggered\"; n/r where the\n"
      "text says nothing. The paper reports no FDE of its VIO alone on these tests (n/r): it evaluates the VIO on\n"
      "EuRoC by ATE only. *VIL <= paper* compares the VIL odometry FDE with the paper's VIL-SLAM odometry value.\n"
      "*paper MRE*: Table I's MRE of VIL-SLAM and of LOAM against Faro scans of the real buildings, \"×\" where the\n"
      "paper has none (no model of the tunnel and the outdoor test). Its highbay map is \"generated using the globally\n"
      "refined poses\", its huge loop map \"with the odometry estimate\" (no loop was triggered) and LOAM's huge loop\n"
      "map ends where LOAM failed. *VIL + loop MRE <= paper* compares the loop-corrected map's MRE with the paper's\n"
      "VIL-SLAM MRE.\n\n" +
      maps_note(rows) +
      format("Measured %s on %s; the command took %.1f min.\n", doc.date_utc.c_str(), doc.machine.c_str(), doc.wall_s / 60);
  if (!doc.note.empty()) out += "\n" + doc.note + "\n";
  return out;
}

}  // namespace vilslam::eval
