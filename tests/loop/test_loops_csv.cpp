// loops.csv long form (what `vilslam run` writes) and loop_candidates.csv: written records read back
// exactly, rejected candidates stay out of loops.csv, and the long form's extra fields are checked.
#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "common/error.h"
#include "loop/loop_constraints_io.h"
#include "test_util.h"

namespace vilslam::loop {
namespace {

LoopCandidateRecord record(TimeNs u_ns, TimeNs v_ns, const std::string& rejected_by) {
  LoopCandidateRecord r;
  r.candidate_t_ns = u_ns;
  r.query_t_ns = v_ns;
  r.T_Lu_Lv = SE3(Quat(Eigen::AngleAxisd(0.3, Vec3(0.2, 0.5, 1.0).normalized())), Vec3(1.25, -0.5, 0.125));
  r.T_Lu_Lv_epnp = SE3(Quat(Eigen::AngleAxisd(0.31, Vec3(0.2, 0.5, 1.0).normalized())), Vec3(1.3, -0.45, 0.1));
  r.information = information_from_sigmas(0.02, 0.004);
  r.bow_score = 0.125;
  r.descriptor_matches = 140;
  r.pnp_inliers = 88;
  r.icp_rms_m = 0.03125;
  r.icp_matched_fraction = 0.625;
  r.icp_inlier_fraction = 0.875;
  r.icp_min_eigenvalue_per_match = 0.25;
  r.epnp_icp_translation_m = 0.0625;
  r.epnp_icp_rotation_rad = 0.01;
  r.odometry_disagreement_m = 0.5;
  r.rejected_by = rejected_by;
  return r;
}

std::string write(const std::string& text) {
  const auto path = test::temp_dir() / "loops.csv";
  std::ofstream(path) << text;
  return path.string();
}

TEST(LoopsCsv, LongFormReadsBackEveryAcceptedRecord) {
  const std::vector<LoopCandidateRecord> records = {record(1'000'000'000, 41'000'000'000, ""),
                                                    record(2'000'000'000, 42'000'000'000, "pnp_inliers"),
                                                    record(3'000'000'000, 43'000'000'000, "")};
  const std::vector<LoopRow> rows = read_loop_rows(write(loops_csv(records)));
  ASSERT_EQ(rows.size(), 2u);  // the rejected candidate is not a loop
  for (std::size_t i = 0; i < 2; ++i) {
    const LoopCandidateRecord& r = records[i == 0 ? 0 : 2];
    EXPECT_EQ(rows[i].from_t_ns, r.candidate_t_ns);
    EXPECT_EQ(rows[i].to_t_ns, r.query_t_ns);
    EXPECT_LT((rows[i].T_from_to.matrix() - r.T_Lu_Lv.matrix()).norm(), 1e-15);
    ASSERT_TRUE(rows[i].T_from_to_epnp && rows[i].sigmas && rows[i].scores);
    EXPECT_LT((rows[i].T_from_to_epnp->matrix() - r.T_Lu_Lv_epnp.matrix()).norm(), 1e-15);
    EXPECT_DOUBLE_EQ(rows[i].sigmas->sigma_m, 0.02);
    EXPECT_DOUBLE_EQ(rows[i].sigmas->sigma_rad, 0.004);
    EXPECT_EQ(rows[i].scores->pnp_inliers, 88);
    EXPECT_EQ(rows[i].scores->icp_inlier_fraction, 0.875);
    EXPECT_EQ(rows[i].scores->odometry_disagreement_m, 0.5);
  }
}

TEST(LoopsCsv, CandidatesNameTheRejectingStage) {
  const std::string text = loop_candidates_csv({record(1, 2, ""), record(3, 4, "icp_degenerate")});
  EXPECT_NE(text.find(",accepted\n"), std::string::npos) << text;
  EXPECT_NE(text.find(",icp_degenerate\n"), std::string::npos) << text;
  EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 3);
  // 14 numbers and the stage per row, the matched fraction (the fitness gate's first test) before the stage.
  const std::string first_row = text.substr(text.find('\n') + 1, text.find(",accepted\n") - text.find('\n') - 1);
  EXPECT_EQ(std::count(first_row.begin(), first_row.end(), ','), 13) << first_row;
  EXPECT_NE(text.find(",0.625,accepted\n"), std::string::npos) << text;
}

TEST(LoopsCsv, BadLongFormRowsNameFileAndLine) {
  std::string good = loops_csv({record(1'000'000'000, 41'000'000'000, "")});
  good = good.substr(good.find('\n') + 1);  // the data row
  const std::string with_nan = good.substr(0, good.rfind(',')) + ",nan\n";
  std::string bad_epnp_quaternion = good;
  {
    // The EPnP qw (field 18) scaled: not a unit quaternion.
    std::size_t pos = 0;
    for (int i = 0; i < 17; ++i) pos = bad_epnp_quaternion.find(',', pos) + 1;
    bad_epnp_quaternion.insert(pos, "3");
  }
  for (const std::string& row : {with_nan, bad_epnp_quaternion, good.substr(0, good.rfind(',')) + "\n"}) {
    const std::string path = write("# header\n" + row);
    try {
      read_loop_rows(path);
      ADD_FAILURE() << "accepted: " << row;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("loops.csv:2"), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace vilslam::loop
