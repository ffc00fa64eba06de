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

// Whether the VIL FDE reaches the paper's VIL-SLAM odometry FDE.
std::string meets_paper(const OdometryRow& row, const std::optional<PaperOdometry>& paper) {
  if (!paper) return "–";
  if (row.vil.lost) return "no (lost)";
  return row.vil.fde_percent <= paper->vil_slam_fde_percent ? "yes" : "no";
}

void append_lost(std::string& out, const OdometryRow& row, const char* name, const DriftResult& d) {
  if (!d.lost) return;
  out += format("- %s, %s: lost, %s", row.preset.c_str(), name, d.lost_reason.c_str());
  if (d.poses >= 2 && d.path_length_m > 0)
    out += format(" (%zu poses; FDE %.3f %%, %.3f m; ATE RMSE %.3f m)", d.poses, d.fde_percent, d.drift_m, d.ate_rmse_m);
  out += "\n";
}

}  // namespace

std::string odometry_table_markdown(const std::vector<OdometryRow>& rows) {
  std::string out =
      "| preset | simulation | length (m) | GT end-start gap (m) | VIO FDE | VIL FDE | LiDAR-only FDE | paper VIL-SLAM | "
      "paper LOAM | paper VIO | VIL <= paper | degenerate sweeps VIL / LiDAR-only | ATE RMSE VIO / VIL / LiDAR-only (m) | "
      "ATE RMSE se3 VIO / VIL (m) |\n"
      "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const OdometryRow& row : rows) {
    const std::optional<PaperOdometry> paper = paper_odometry(row.preset);
    out += format("| %s | %s | %.1f | %.3f | %s | %s | %s | ", row.preset.c_str(), row.source.c_str(), row.gt_length_m,
                  row.gt_gap_m, fde_cell(row.vio, row.closed).c_str(), fde_cell(row.vil, row.closed).c_str(),
                  fde_cell(row.lidar_only, row.closed).c_str());
    out += paper ? format("%.2f %% (%.0f m) | %s | n/r | ", paper->vil_slam_fde_percent, paper->length_m,
                          paper_fde(paper->loam_fde_percent).c_str())
                 : std::string("– | – | – | ");
    out += format("%s | %zu of %zu / %zu of %zu | %s / %s / %s | %s / %s |\n", meets_paper(row, paper).c_str(),
                  row.vil_degenerate, row.vil_sweeps, row.lidar_only_degenerate, row.lidar_only_sweeps,
                  ate_cell(row.vio, false).c_str(), ate_cell(row.vil, false).c_str(), ate_cell(row.lidar_only, false).c_str(),
                  ate_cell(row.vio, true).c_str(), ate_cell(row.vil, true).c_str());
  }
  std::string lost;
  for (const OdometryRow& row : rows) {
    append_lost(lost, row, "VIO", row.vio);
    append_lost(lost, row, "VIL", row.vil);
    append_lost(lost, row, "LiDAR-only", row.lidar_only);
  }
  if (!lost.empty()) out += "\nLost runs:\n\n" + lost;
  return out;
}

std::string odometry_document_markdown(const std::vector<OdometryRow>& rows, const OdometryDocument& doc) {
  std::string out =
      "# Odometry on the simulated presets: VIO, VIL and LiDAR-only final drift\n\n"
      "The odometry part of the paper's Table I on the simulator's presets (docs/simulator.md): each dataset is\n"
      "run in `vil` mode (frontend + VIO, LiDAR mapping with the VIO's IMU-rate poses as motion prior) and in\n"
      "`lidar-only` mode (the mapper with a constant-velocity model, the paper's LOAM baseline), as\n"
      "`vilslam run` does (docs/pipeline.md); no loop closure runs. The VIO-only trajectory is the `vil` run's\n"
      "camera-rate states (`vio_camera.tum`): the LiDAR never feeds back into the VIO.\n\n"
      "Made by one command (`apps/vilslam/cmd_odometry_table.cpp`, `src/eval/odometry_table.h`):\n\n    " +
      doc.command +
      "\n\n"
      "It reuses `WORK/<preset>` when that folder already holds a complete simulation, else simulates it there\n"
      "(`vilslam simulate <preset> --seed S`), and writes the runs to `WORK/<preset>_vil` and\n"
      "`WORK/<preset>_lidar-only` (the files of `vilslam run`).\n\n"
      "## Definitions\n\n"
      "- **FDE** (final drift error, the paper's odometry measure): the distance between the estimate's last and\n"
      "  first position over the estimate's path length, in %. It measures drift only when the route closes: the\n"
      "  column *GT end-start gap* is that distance for the ground truth (IMU and LiDAR frames, the larger); a\n"
      "  route closes when it is at most 0.01 m. On a route that does not close (marked †), the FDE is instead\n"
      "  the drift against ground truth: the estimate moved rigidly onto the first ground-truth pose, the distance\n"
      "  between its last position and the last ground-truth position, over the ground-truth path length.\n"
      "- **VIO**: camera-rate VIO states `T_W_I`; **VIL** and **LiDAR-only**: LiDAR mapping poses `T_W_L`, one\n"
      "  per sweep, compared with the ground truth moved into the LiDAR frame (`T_W_I T_I_L`).\n"
      "- **ATE RMSE**: APE translation RMSE after alignment (docs/evaluation.md): `posyaw` for VIO and VIL (the\n"
      "  VIO's world is gravity aligned, yaw and position are unobservable), `se3` for LiDAR-only (it starts in\n"
      "  the first sweep's frame). The posyaw alignment keeps the roll and pitch of the estimate's world (the\n"
      "  VIO's gravity estimate at initialization, which the VIL map inherits); the last column aligns VIO and\n"
      "  VIL in SE(3) as well, so the difference between the two shows that tilt.\n"
      "- **Lost**: the run threw, gave fewer than 2 poses or a non-finite pose, spans less than 50 % of the\n"
      "  sequence, or after the ATE alignment some pose lies farther from ground truth than 10 % of the path\n"
      "  length (at least 1 m). A lost run's FDE is not tabulated; its reason and numbers are listed below the table.\n"
      "- **Degenerate sweeps**: sweeps the mapper flagged degenerate (an eigenvalue of `J^T J` below its\n"
      "  threshold, docs/lidar.md), of the sweeps mapped.\n"
      "- **length**: the ground truth's path length.\n\n"
      "## Table\n\n" +
      odometry_table_markdown(rows) +
      "\n"
      "Paper values: VIL-SLAM paper Table I (\"FDE (%) and MRE (m) test results\"), odometry FDE of VIL-SLAM and\n"
      "of LOAM (laboshinl/loam_velodyne) on the real tests of the same names, with their path lengths;\n"
      "\"not finished\" is the paper's \"-\". Loop closure lowered the paper's hallway FDE to 0.05 % and its tunnel\n"
      "FDE to 0.08 % (text of its results section); these are not odometry values. The paper reports no FDE of\n"
      "its VIO alone on these tests (n/r): it evaluates the VIO on EuRoC by ATE only. *VIL <= paper* compares the\n"
      "VIL FDE with the paper's VIL-SLAM value.\n\n" +
      format("Measured %s on %s; the command took %.1f min.\n", doc.date_utc.c_str(), doc.machine.c_str(), doc.wall_s / 60);
  if (!doc.note.empty()) out += "\n" + doc.note + "\n";
  return out;
}

}  // namespace vilslam::eval
