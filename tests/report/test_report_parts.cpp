// The report's parts: decimation, histograms, the base64 float32 encoding, per-pose errors, and the page.
#include <gtest/gtest.h>

#include <numeric>

#include "eval/trajectory_eval.h"
#include "report/base64.h"
#include "report/decimate.h"
#include "report/histogram.h"
#include "report/report_html.h"
#include "report/synthetic_run.h"
#include "report/trajectory_errors.h"

namespace vilslam::report {
namespace {

TEST(Decimate, KeepsEveryKthAndTheLast) {
  EXPECT_EQ(decimated_indices(10, 3), (std::vector<std::size_t>{0, 4, 8, 9}));
  EXPECT_EQ(decimated_indices(4, 4), (std::vector<std::size_t>{0, 1, 2, 3}));
  EXPECT_EQ(decimated_indices(9, 3), (std::vector<std::size_t>{0, 3, 6, 8}));
  EXPECT_TRUE(decimated_indices(0, 3).empty());
  for (std::size_t n : {1000u, 1001u, 54321u}) EXPECT_LE(decimated_indices(n, 200).size(), 201u) << n;
  EXPECT_THROW(decimated_indices(5, 0), std::invalid_argument);
}

TEST(Histogram, EverySampleInOneBinFromZeroToTheLargest) {
  const Histogram h = histogram_from_zero({0.0, 0.5, 1.0, 2.49, 2.5, 9.99, 10.0}, 4);
  EXPECT_EQ(h.lower, 0.0);
  EXPECT_EQ(h.bin_width, 2.5);
  EXPECT_EQ(h.counts, (std::vector<std::size_t>{4, 1, 0, 2}));  // 10.0 belongs to the last bin
  EXPECT_TRUE(histogram_from_zero({}, 4).counts.empty());
  EXPECT_EQ(histogram_from_zero({0.0, 0.0}, 4).counts, (std::vector<std::size_t>{2}));
}

TEST(Base64, LittleEndianFloat32) {
  EXPECT_EQ(base64_float32({}), "");
  EXPECT_EQ(base64_float32({1.0f}), "AACAPw==");          // 00 00 80 3f
  EXPECT_EQ(base64_float32({1.0f, -2.0f}), "AACAPwAAAMA=");  // 00 00 80 3f 00 00 00 c0
  EXPECT_EQ(base64_float32({0.5f, 0.5f, 0.5f}), "AAAAPwAAAD8AAAA/");
}

TEST(TrajectoryErrors, PerPoseErrorsOverTimeAndDistance) {
  const Trajectory gt = test::circle_T_W_B();
  const SE3 T_other_W(Quat(Eigen::AngleAxisd(0.7, Vec3::UnitZ())), Vec3(3, 1, -0.5));
  Trajectory est = test::drifted(gt, T_other_W, 0.3);
  est.erase(est.begin() + 50, est.begin() + 60);  // a gap: those ground-truth poses go unmatched
  const TrajectoryErrors e = trajectory_errors(est, gt, eval::AlignMode::kSe3);
  eval::TrajectoryEvalConfig config;
  const eval::TrajectoryEvalReport reference = eval::evaluate_trajectory(est, gt, config);
  ASSERT_EQ(e.t_ns.size(), est.size());
  EXPECT_EQ(e.ape.trans_m.size(), reference.ape.trans_m.size());
  EXPECT_DOUBLE_EQ(e.ape.trans.rmse, reference.ape.trans.rmse);
  EXPECT_GT(e.ape.trans.rmse, 0.01);
  for (std::size_t i = 0; i < est.size(); ++i) EXPECT_EQ(e.t_ns[i], est[i].t_ns);
  // The travelled distance grows with the path: the last is the whole path's length (a 5 m circle, 2 pi r
  // and a little from the drift and the height wave), and it jumps over the gap by the gap's chord.
  EXPECT_EQ(e.travelled_m.front(), 0.0);
  EXPECT_NEAR(e.travelled_m.back(), reference.path_length_m, 1e-9);
  EXPECT_GT(e.travelled_m.back(), 2 * M_PI * 5 * 0.99);
  for (std::size_t i = 1; i < e.travelled_m.size(); ++i) EXPECT_GT(e.travelled_m[i], e.travelled_m[i - 1]);
  // The aligned estimate lies in the ground truth's world: its first pose within the drift of gt's.
  EXPECT_LT((e.est_in_gt_world.front().T_W_B.translation() - gt.front().T_W_B.translation()).norm(), 0.3);
  EXPECT_EQ(e.est_in_gt_world.size(), est.size());
}

TEST(ReportHtml, OneFileWithEverythingInline) {
  const std::string html = report_html("{\"run\": \"a</script><b>\"}\n");
  EXPECT_NE(html.find("{\"run\": \"a<\\/script><b>\"}"), std::string::npos);  // cannot end the data early
  EXPECT_EQ(html.find("a</script>"), std::string::npos);
  EXPECT_NE(html.find("Chart.js v"), std::string::npos);  // the libraries are inline, nothing is fetched
  EXPECT_NE(html.find("REVISION"), std::string::npos);
  EXPECT_NE(html.find("OrbitControls"), std::string::npos);
  for (const char* remote : {"src=\"http", "href=\"http", "src=\"//", "<link "})
    EXPECT_EQ(html.find(remote), std::string::npos) << remote;
  EXPECT_NE(html.find("id=\"report-status\""), std::string::npos);
}

}  // namespace
}  // namespace vilslam::report
