// `vilslam odometry-table` end to end on a preview highbay: simulated when missing, reused when present,
// the page holds the numbers `vilslam eval` and `vilslam map` + `vilslam eval-map` give, `--config` reaches
// both runs; bad input exits 2.
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>

#include "eval/trajectory_eval.h"
#include "io/dataset.h"
#include "io/groundtruth_mounts.h"
#include "io/trajectory_io.h"
#include "cli_output.h"
#include "test_util.h"

namespace vilslam {
namespace {

namespace fs = std::filesystem;

using test::json_number;

std::string fixed3(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3f", v);
  return buf;
}

// The table's line of a preset.
std::string table_row(const std::string& page, const std::string& preset) {
  const auto at = page.find("| " + preset + " |");
  return at == std::string::npos ? std::string() : page.substr(at, page.find('\n', at) - at);
}

// The row from its third cell on (the cells after preset and simulation).
std::string after_source(const std::string& row) {
  std::size_t at = 0;
  for (int i = 0; i < 3; ++i) at = row.find('|', at) + 1;
  return row.substr(at);
}

TEST(CmdOdometryTable, PreviewHighbaySimulatesThenReuses) {
  const fs::path dir = test::temp_dir();
  const fs::path work = dir / "work", page = dir / "odometry.md";
  const test::CliResult r = test::run_cli("odometry-table --work " + work.string() +
                                          " --presets highbay --seed 3 --preview --out " + page.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  for (const char* sub : {"highbay/groundtruth.tum", "highbay_vil/vio_camera.tum", "highbay_vil/lidar.tum",
                          "highbay_vil/lidar_final.tum", "highbay_vil/loops.csv",
                          "highbay_lidar-only/lidar.tum", "highbay_lidar-only/degeneracy.csv"})
    EXPECT_TRUE(fs::exists(work / sub)) << sub;
  const std::string text = test::read_file_bytes(page);
  const std::string row = table_row(text, "highbay");
  ASSERT_FALSE(row.empty()) << text;
  EXPECT_NE(row.find("| simulated, seed 3, preview |"), std::string::npos) << row;
  EXPECT_NE(r.output.find(row), std::string::npos) << "the table is printed too";
  EXPECT_NE(text.find("odometry-table --work " + work.string() + " --presets highbay --seed 3 --preview --map-voxel 0.05 --out"),
            std::string::npos);

  // The preview does not return to its start: the VIO FDE is the start-aligned drift `vilslam eval` reports.
  const fs::path json = dir / "vio.json";
  const test::CliResult ev = test::run_cli("eval --est " + (work / "highbay_vil/vio_camera.tum").string() + " --gt " +
                                           (work / "highbay/groundtruth.tum").string() + " --align posyaw --json " +
                                           json.string());
  ASSERT_EQ(ev.exit_code, 0) << ev.output;
  const std::string doc = test::read_file_bytes(json);
  EXPECT_NE(row.find("| " + fixed3(json_number(doc, "fde_start_aligned_percent", "fde_start_aligned_percent")) + " %†"),
            std::string::npos)
      << row;
  EXPECT_NE(row.find("| " + fixed3(json_number(doc, "ape", "rmse")) + " / "), std::string::npos) << row;
  const fs::path json_se3 = dir / "vio_se3.json";
  ASSERT_EQ(test::run_cli("eval --est " + (work / "highbay_vil/vio_camera.tum").string() + " --gt " +
                          (work / "highbay/groundtruth.tum").string() + " --align se3 --json " + json_se3.string())
                .exit_code,
            0);
  EXPECT_NE(row.find("| " + fixed3(json_number(test::read_file_bytes(json_se3), "ape", "rmse")) + " / "), std::string::npos) << row;

  // LiDAR-only ATE (se3) against the ground truth in the LiDAR frame, from the written lidar.tum. The preview is
  // simulated with sensor realism: the LiDAR's ground truth goes through its true mount, not the calibration's.
  const auto reader = open_dataset((work / "highbay").string());
  const std::optional<GroundTruthMounts> mounts = read_groundtruth_mounts((work / "highbay").string());
  ASSERT_TRUE(mounts);
  Trajectory gt_L;
  for (const GroundTruthState& g : reader->groundtruth()) gt_L.push_back({g.t_ns, g.T_W_I * mounts->T_I_L});
  eval::TrajectoryEvalConfig se3;
  const eval::TrajectoryEvalReport lidar_only = eval::evaluate_trajectory(
      read_trajectory((work / "highbay_lidar-only/lidar.tum").string(), TrajectoryFormat::kTum), gt_L, se3);
  EXPECT_NE(row.find(" / " + fixed3(lidar_only.ape.trans.rmse) + " |"), std::string::npos) << row;
  EXPECT_LT(lidar_only.ape.trans.rmse, 0.10);

  // The loop-closed trajectory: FDE (start-aligned, posyaw) and SE(3) ATE from the written lidar_final.tum.
  // The 1.5 s preview revisits nothing: no candidate is examined, no loop accepted, no median error.
  const Trajectory lidar_final = read_trajectory((work / "highbay_vil/lidar_final.tum").string(), TrajectoryFormat::kTum);
  eval::TrajectoryEvalConfig posyaw;
  posyaw.align = eval::AlignMode::kPosYaw;
  const eval::TrajectoryEvalReport final_posyaw = eval::evaluate_trajectory(lidar_final, gt_L, posyaw);
  EXPECT_NE(row.find(" | " + fixed3(final_posyaw.fde_start_aligned.percent) + " %† (" +
                     fixed3(final_posyaw.fde_start_aligned.drift_m) + " m) | "),
            std::string::npos)
      << row;
  const eval::TrajectoryEvalReport final_se3 = eval::evaluate_trajectory(lidar_final, gt_L, se3);
  EXPECT_NE(row.find(" / " + fixed3(final_se3.ape.trans.rmse) + " | 0 / 0 / 0 | – |"), std::string::npos) << row;

  // The MRE of the odometry map: `vilslam map` with the table's voxel, then `eval-map` from the first pose.
  const fs::path map = dir / "vil_map.ply", mre_json = dir / "vil_mre.json";
  const std::string lidar_tum = (work / "highbay_vil/lidar.tum").string(), data = (work / "highbay").string();
  ASSERT_EQ(test::run_cli("map " + data + " --poses " + lidar_tum + " --voxel 0.05 --out " + map.string()).exit_code, 0);
  const test::CliResult mre = test::run_cli("eval-map --map " + map.string() + " --model " + data + "/model.ply" +
                                            " --first-pose " + lidar_tum + " --gt " + data + " --json " + mre_json.string());
  ASSERT_EQ(mre.exit_code, 0) << mre.output;
  const std::string mre_doc = test::read_file_bytes(mre_json);
  const double vil_mre_m = json_number(mre_doc, "mean_m", "mean_m");
  const bool converged = mre_doc.find("\"converged\": true") != std::string::npos;
  EXPECT_LT(vil_mre_m, 0.2);
  EXPECT_NE(row.find("| " + fixed3(vil_mre_m) + (converged ? "" : "*") + " / "), std::string::npos) << row;
  EXPECT_NE(row.find(" | 0.08 / 0.22 | "), std::string::npos) << row;  // the paper's highbay MRE
  EXPECT_NE(text.find("Dense maps in voxels of 0.050 m"), std::string::npos) << text;

  // A second work folder whose highbay is a link to the first: reused, same numbers.
  // Its --config (loop closure off) reaches both runs; with no loop in the preview the numbers stay.
  const fs::path work2 = dir / "work2", page2 = dir / "odometry2.md", config = dir / "no_loops.yaml";
  fs::create_directories(work2);
  fs::create_directory_symlink(work / "highbay", work2 / "highbay");
  std::ofstream(config) << "loop_closure:\n  enabled: false\n";
  const test::CliResult again = test::run_cli("odometry-table --work " + work2.string() +
                                              " --presets highbay --seed 3 --preview --config " + config.string() +
                                              " --out " + page2.string());
  ASSERT_EQ(again.exit_code, 0) << again.output;
  EXPECT_EQ(again.output.find("simulate highbay"), std::string::npos) << again.output;
  const std::string row2 = table_row(test::read_file_bytes(page2), "highbay");
  EXPECT_NE(row2.find("| reused `" + (work2 / "highbay").string() + "` → `"), std::string::npos) << row2;
  EXPECT_EQ(after_source(row2), after_source(row));
  for (const char* run : {"highbay_vil/config.yaml", "highbay_lidar-only/config.yaml"}) {
    const std::string yaml = test::read_file_bytes(work2 / run);
    EXPECT_NE(yaml.find("enabled: false"), std::string::npos) << run;
  }
  EXPECT_NE(test::read_file_bytes(page2).find(" --config " + config.string() + " --map-voxel 0.05 --out "), std::string::npos);

  // --reuse-runs reads the first work folder's runs back (made with the default config): no run, same row.
  // With another config the runs are made again.
  const fs::path page3 = dir / "odometry3.md";
  const fs::file_time_type vil_written = fs::last_write_time(work / "highbay_vil" / "lidar.tum");
  const test::CliResult reused = test::run_cli("odometry-table --work " + work.string() +
                                               " --presets highbay --seed 3 --preview --reuse-runs --out " +
                                               page3.string());
  ASSERT_EQ(reused.exit_code, 0) << reused.output;
  EXPECT_NE(reused.output.find("reusing " + (work / "highbay_vil").string()), std::string::npos) << reused.output;
  EXPECT_NE(reused.output.find("reusing " + (work / "highbay_lidar-only").string()), std::string::npos);
  EXPECT_EQ(reused.output.find("vil on "), std::string::npos) << reused.output;
  EXPECT_EQ(fs::last_write_time(work / "highbay_vil" / "lidar.tum"), vil_written);
  EXPECT_EQ(after_source(table_row(test::read_file_bytes(page3), "highbay")), after_source(row));
  const test::CliResult rerun = test::run_cli("odometry-table --work " + work2.string() +
                                              " --presets highbay --seed 3 --preview --reuse-runs --no-maps --out " +
                                              (dir / "odometry4.md").string());
  ASSERT_EQ(rerun.exit_code, 0) << rerun.output;
  EXPECT_NE(rerun.output.find("made with another config"), std::string::npos) << rerun.output;
}

TEST(CmdOdometryTable, BadInputExitsTwo) {
  const fs::path dir = test::temp_dir();
  const std::string work = (dir / "work").string(), page = (dir / "t.md").string();
  EXPECT_EQ(test::run_cli("odometry-table --work " + work + " --presets highbay,mars --out " + page).exit_code, 2);
  EXPECT_EQ(test::run_cli("odometry-table --work " + work + " --presets highbay --out " + (dir / "no/t.md").string())
                .exit_code,
            2);
  const fs::path bad_config = dir / "bad.yaml";
  std::ofstream(bad_config) << "loop_closure:\n  enabeld: false\n";
  EXPECT_EQ(test::run_cli("odometry-table --work " + work + " --presets highbay --config " + bad_config.string() +
                          " --out " + page)
                .exit_code,
            2);
  EXPECT_EQ(test::run_cli("odometry-table --work " + work + " --presets highbay --map-voxel 0 --out " + page).exit_code, 2);
  EXPECT_FALSE(fs::exists(dir / "work"));
  fs::create_directories(dir / "work" / "highbay");  // not a complete simulation
  EXPECT_EQ(test::run_cli("odometry-table --work " + work + " --presets highbay --out " + page).exit_code, 2);
  EXPECT_FALSE(fs::exists(page));
  EXPECT_FALSE(fs::exists(dir / "work" / "highbay_vil"));
}

}  // namespace
}  // namespace vilslam
