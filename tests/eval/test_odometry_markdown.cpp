// Markdown of the odometry table: cells, the paper's values, lost runs, the page around the table.
#include <gtest/gtest.h>

#include <string>

#include "eval/odometry_markdown.h"

namespace vilslam::eval {
namespace {

DriftResult drift(double percent, double drift_m, double ate_m, double ate_se3_m) {
  DriftResult d;
  d.poses = 100;
  d.fde_percent = percent;
  d.drift_m = drift_m;
  d.path_length_m = 100 * drift_m / percent;
  d.ate_rmse_m = ate_m;
  d.ate_se3_rmse_m = ate_se3_m;
  return d;
}

OdometryRow highbay() {
  OdometryRow row;
  row.preset = "highbay";
  row.source = "reused `/tmp/ot/highbay`";
  row.gt_length_m = 117.84;
  row.closed = true;
  row.vio = drift(0.292, 0.342, 0.126, 0.1147);
  row.vil = drift(0.0104, 0.0123, 0.171, 0.0272);
  row.lidar_only = drift(0.0152, 0.018, 0.033, 0.033);
  row.vil_final = drift(0.0031, 0.0036, 0.160, 0.0119);
  LoopClosureResult loops;
  loops.candidates_examined = 12;
  loops.accepted.loops.resize(3);
  loops.accepted.false_loops = 1;
  loops.accepted.median_translation_m = 0.0214;
  loops.accepted.median_rotation_deg = 0.317;
  loops.accepted.median_epnp_translation_m = 0.0876;
  loops.accepted.median_epnp_rotation_deg = 1.204;
  row.loops = loops;
  row.vil_sweeps = 1021;
  row.lidar_only_sweeps = 1022;
  row.lidar_only_degenerate = 4;
  return row;
}

std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (auto at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

TEST(OdometryMarkdown, RowCells) {
  const std::string table = odometry_table_markdown({highbay()});
  EXPECT_EQ(count(table, "\n"), 3u) << table;  // header, rule, one row
  const std::string row = table.substr(table.find("| highbay"));
  EXPECT_NE(row.find("| reused `/tmp/ot/highbay` | 117.8 | 0.000 |"), std::string::npos) << row;
  EXPECT_NE(row.find("| 0.292 % (0.342 m) | 0.010 % (0.012 m) | 0.015 % (0.018 m) | 0.003 % (0.004 m) |"),
            std::string::npos)
      << row;
  EXPECT_NE(row.find("| 0.08 % (118 m) | 0.56 % | n/r | closes the loop, no FDE given | yes |"), std::string::npos) << row;
  EXPECT_NE(row.find("| 0 of 1021 / 4 of 1022 | 0.126 / 0.171 / 0.033 | 0.115 / 0.027 / 0.012 |"), std::string::npos)
      << row;
  EXPECT_NE(row.find("| 12 / 3 / 1 | 0.021 m 0.32° / 0.088 m 1.20° | not measured | 0.08 / 0.22 | – |\n"),
            std::string::npos)
      << row;
  for (const char* column : {"| VIL + loop FDE |", "| paper VIL-SLAM + loop |", "| ATE RMSE se3 VIO / VIL / VIL + loop (m) |",
                             "| loops examined / accepted / false |", "| median loop error EPnP+ICP / EPnP |",
                             "| MRE VIL / VIL + loop / LiDAR-only / true poses (m) |", "| paper MRE VIL-SLAM / LOAM (m) |",
                             "| VIL + loop MRE <= paper |"})
    EXPECT_NE(table.find(column), std::string::npos) << column;
  EXPECT_EQ(row.find("†"), std::string::npos);
  EXPECT_EQ(table.find("Lost runs"), std::string::npos);
  // Every line has the header's 21 columns.
  for (std::size_t start = 0, end; (end = table.find('\n', start)) != std::string::npos; start = end + 1)
    EXPECT_EQ(count(table.substr(start, end - start), "|"), 22u) << table.substr(start, end - start);
}

TEST(OdometryMarkdown, LostRunsOpenRoutesAndPresetsWithoutPaperValues) {
  OdometryRow tunnel = highbay();
  tunnel.preset = "tunnel";
  tunnel.vil = drift(2.5, 2.1, 0.9, 0.8);
  tunnel.lidar_only = drift(30.0, 25.0, 9.0, 9.0);
  tunnel.lidar_only.lost = true;
  tunnel.lidar_only.lost_reason = "strays 14.00 m from ground truth (limit 8.50 m)";
  tunnel.loops->candidates_examined = 4;
  tunnel.loops->accepted = LoopEvaluation{};  // none accepted: no median error
  OdometryRow room = highbay();
  room.preset = "room";
  room.closed = false;
  room.gt_gap_m = 2.5;
  room.loops.reset();  // the VIL run failed
  room.vil_final.lost = true;
  room.vil_final.lost_reason = "the run failed: no key image";
  const std::string table = odometry_table_markdown({tunnel, room});
  const std::string tunnel_row = table.substr(table.find("| tunnel"), table.find("| room") - table.find("| tunnel"));
  EXPECT_NE(tunnel_row.find("| 2.500 % (2.100 m) | **lost** |"), std::string::npos) << tunnel_row;
  EXPECT_NE(tunnel_row.find("| 1.86 % (85 m) | not finished | n/r | 0.08 % | no |"), std::string::npos) << tunnel_row;
  EXPECT_NE(tunnel_row.find("| 4 / 0 / 0 | – | not measured | × / × | – |\n"), std::string::npos) << tunnel_row;
  EXPECT_NE(table.find("Lost runs:\n\n- tunnel, LiDAR-only: lost, strays 14.00 m from ground truth (limit 8.50 m) "
                       "(100 poses; FDE 30.000 %, 25.000 m; ATE RMSE 9.000 m)\n"),
            std::string::npos)
      << table;
  const std::string room_row = table.substr(table.find("| room"));
  EXPECT_NE(room_row.find("| 2.500 | 0.292 %† (0.342 m) |"), std::string::npos) << room_row;
  EXPECT_NE(room_row.find("| **lost** | – | – | – | – |"), std::string::npos) << room_row;
  EXPECT_NE(room_row.find("| – | – | not measured | – | – |\n"), std::string::npos) << room_row;
  EXPECT_NE(table.find("- room, VIL + loop: lost, the run failed: no key image"), std::string::npos) << table;
}

MapRegistration mre(double mean_m, bool converged = true) {
  MapRegistration m;
  m.points = 1000;
  m.mean_m = mean_m;
  m.icp_converged = converged;
  m.wall_s = 30;
  return m;
}

// The MRE cells: four maps (an ICP that did not converge starred, a lost run's map missing and listed),
// the paper's MRE, the comparison with it, the voxel size and time on the page.
TEST(OdometryMarkdown, MreCells) {
  OdometryRow row = highbay();
  MapErrors maps;
  maps.voxel_m = 0.05;
  maps.vil = mre(0.0412);
  maps.vil_final = mre(0.0307, false);
  maps.lidar_only.failure = "the run is lost";
  maps.truth = mre(0.0184);
  row.maps = maps;
  const std::string table = odometry_table_markdown({row});
  EXPECT_NE(table.find("| 0.041 / 0.031* / – / 0.018 | 0.08 / 0.22 | yes |\n"), std::string::npos) << table;
  EXPECT_NE(table.find("Dense maps without MRE:\n\n- highbay, LiDAR-only map: the run is lost\n"), std::string::npos)
      << table;
  row.maps->vil_final.mean_m = 0.09;
  EXPECT_NE(odometry_table_markdown({row}).find("| 0.08 / 0.22 | no |\n"), std::string::npos);
  row.maps->vil_final.failure = "ICP: fewer than 6 correspondences within range";
  EXPECT_NE(odometry_table_markdown({row}).find("| 0.041 / – / – / 0.018 | 0.08 / 0.22 | no (no map) |\n"),
            std::string::npos);

  const std::string page = odometry_document_markdown({row}, OdometryDocument{});
  EXPECT_NE(page.find("Dense maps in voxels of 0.050 m"), std::string::npos) << page;
  EXPECT_NE(page.find("Building and measuring the 2 maps took 1.5 min."), std::string::npos) << page;
  EXPECT_NE(page.find("aligned to the model by the first pose only, then ICP"), std::string::npos);
  EXPECT_NE(odometry_document_markdown({highbay()}, OdometryDocument{}).find("not measured (`--no-maps`)"),
            std::string::npos);
}

TEST(OdometryMarkdown, DocumentHasCommandTableDateAndNote) {
  OdometryDocument doc;
  doc.command = "vilslam odometry-table --work /tmp/ot --presets highbay --seed 1 --out docs/odometry.md";
  doc.date_utc = "2026-11-22 15:40 UTC";
  doc.machine = "vm (x86_64, 2 hardware threads)";
  doc.wall_s = 750;
  doc.note = "highbay was simulated with seed 1.";
  const std::string page = odometry_document_markdown({highbay()}, doc);
  EXPECT_EQ(page.rfind("# ", 0), 0u);
  EXPECT_NE(page.find("\n    " + doc.command + "\n"), std::string::npos);
  EXPECT_NE(page.find(odometry_table_markdown({highbay()})), std::string::npos);
  EXPECT_NE(page.find("Measured 2026-11-22 15:40 UTC on vm (x86_64, 2 hardware threads); the command took 12.5 min."),
            std::string::npos);
  EXPECT_NE(page.find("\nhighbay was simulated with seed 1.\n"), std::string::npos);
  // The definitions of the loop closure columns and the paper's after-loop figures with their caveats.
  for (const char* text : {"**VIL + loop** is the loop-closed trajectory (`lidar_final.tum`", "more than 0.3 m or 3°",
                           "EPnP + ICP (the constraint)\n  / EPnP alone", "hallway FDE to 0.05 %", "tunnel FDE to 0.08 %",
                           "\"without loop closure being triggered\"", "`--config RUN_YAML`"})
    EXPECT_NE(page.find(text), std::string::npos) << text;
}

}  // namespace
}  // namespace vilslam::eval
