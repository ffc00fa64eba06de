// A sweep's status (lidar/mapping_status.h): the first of after gap, not converged, prediction contradicted and
// degenerate that applies, at the documented thresholds.
#include <gtest/gtest.h>

#include "lidar/mapping_status.h"

namespace vilslam::lidar {
namespace {

TEST(MappingStatus, FirstThatAppliesAtTheThresholds) {
  LidarMappingResult sweep;
  EXPECT_EQ(mapping_status(sweep), MappingStatus::kOk);
  sweep.degenerate = true;
  EXPECT_EQ(mapping_status(sweep), MappingStatus::kDegenerate);
  sweep.correction_deg = 3.0;  // at the threshold: not yet
  EXPECT_EQ(mapping_status(sweep), MappingStatus::kDegenerate);
  sweep.correction_deg = 3.1;
  EXPECT_EQ(mapping_status(sweep), MappingStatus::kPredictionContradicted);
  sweep.correction_deg = 0.0;
  sweep.correction_m = 0.31;
  EXPECT_EQ(mapping_status(sweep), MappingStatus::kPredictionContradicted);
  sweep.converged = false;
  EXPECT_EQ(mapping_status(sweep), MappingStatus::kNotConverged);
  sweep.gap_s = 0.04;  // a sweep's own seam, not a missing sweep
  EXPECT_EQ(mapping_status(sweep), MappingStatus::kNotConverged);
  sweep.gap_s = 0.2;
  EXPECT_EQ(mapping_status(sweep), MappingStatus::kAfterGap);
  EXPECT_EQ(mapping_status_name(mapping_status(sweep)), "after_gap");
}

}  // namespace
}  // namespace vilslam::lidar
