#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>

#include "frontend/frontend.h"
#include "frontend/outlier_rejection.h"
#include "io/dataset.h"
#include "test_util.h"

namespace vilslam {
namespace {

// Real EuRoC stereo (V1_01_easy, 95 pairs): enough stereo matches on every pair, sub-pixel stereo geometry.
TEST(FrontendEuroc, KeepsHundredMatchesWithSubpixelStereoError) {
  VILSLAM_REQUIRE_SHARED_DATA(path, "euroc/V1_01_easy_micro");
  const std::unique_ptr<DatasetReader> reader = open_dataset(path);
  Frontend frontend(reader->calibration());
  const StereoRig& rig = frontend.rig();
  std::vector<double> counts, errors_px;
  int extractions = 0;
  while (const std::optional<SensorEvent> event = reader->next()) {
    const auto* frame = std::get_if<StereoFrame>(&event->data);
    if (!frame) continue;
    const FrontendOutput out = frontend.process(*frame);
    counts.push_back(static_cast<double>(out.matches.size()));
    extractions += out.extracted > 0;
    for (const StereoMatch& m : out.matches) {
      Vec3 p_C0;
      ASSERT_TRUE(triangulate_stereo(m.left_norm, m.right_norm, rig.T_C1_C0, &p_C0));
      errors_px.push_back(stereo_reprojection_error_px(rig, p_C0, m.left_px, m.right_px));
    }
  }
  ASSERT_EQ(counts.size(), 95u);
  const double min_count = *std::min_element(counts.begin(), counts.end());
  const double max_count = *std::max_element(counts.begin(), counts.end());
  std::printf("EuRoC V1_01 micro: %zu pairs, stereo matches per pair min %.0f median %.0f max %.0f, "
              "extraction on %d pairs, median stereo reprojection error %.3f px over %zu matches\n",
              counts.size(), min_count, test::median(counts), max_count, extractions, test::median(errors_px), errors_px.size());
  EXPECT_GE(min_count, 100);
  EXPECT_LT(test::median(errors_px), 1.0);
}

}  // namespace
}  // namespace vilslam
