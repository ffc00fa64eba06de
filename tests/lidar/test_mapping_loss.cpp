// When a registered sweep is rejected (lidar/mapping_loss.h): it matched the wrong surfaces, too little of it
// matched after a gap, or the registration moved a prior-aided prediction too far; strictly beyond each
// threshold, and never with the check off. Bad thresholds in a run
// config name the file.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "common/error.h"
#include "lidar/mapping_loss.h"
#include "lidar/mapping_status.h"

namespace vilslam::lidar {
namespace {

TEST(MappingLoss, RejectsBeyondEachThresholdAndNeverWhenOff) {
  const MappingLossConfig c;
  // matched, inliers, gap, correction m, deg, prior-aided
  EXPECT_EQ(mapping_loss({0.75, 0.85, 0.0, 0.05, 0.3, true}, c), MappingLoss::kNone);
  EXPECT_EQ(mapping_loss({0.25, 0.35, 0.15, 1.0, 10.0, true}, c), MappingLoss::kNone);  // at the thresholds: kept
  EXPECT_EQ(mapping_loss({0.75, 0.34, 0.0, 0.0, 0.0, true}, c), MappingLoss::kMismatched);
  // Little of it matched: new space in view, unless its prediction spans a gap.
  EXPECT_EQ(mapping_loss({0.01, 0.9, 0.0, 0.0, 0.0, true}, c), MappingLoss::kNone);
  EXPECT_EQ(mapping_loss({0.0, 0.0, 0.0, 0.0, 0.0, true}, c), MappingLoss::kNone);
  EXPECT_EQ(mapping_loss({0.24, 0.9, 0.16, 0.0, 0.0, true}, c), MappingLoss::kUnmatched);
  EXPECT_EQ(mapping_loss({0.0, 0.0, 5.0, 0.0, 0.0, true}, c), MappingLoss::kUnmatched);
  EXPECT_EQ(mapping_loss({0.75, 0.85, 0.0, 1.01, 0.0, true}, c), MappingLoss::kJump);
  EXPECT_EQ(mapping_loss({0.75, 0.85, 0.0, 0.0, 10.1, true}, c), MappingLoss::kJump);
  // A constant-velocity prediction (no prior) may be off by a turn: no jump, the other two tests still apply.
  EXPECT_EQ(mapping_loss({0.75, 0.85, 0.0, 1.5, 23.0, false}, c), MappingLoss::kNone);
  EXPECT_EQ(mapping_loss({0.75, 0.34, 0.0, 1.5, 23.0, false}, c), MappingLoss::kMismatched);
  EXPECT_EQ(mapping_loss({0.24, 0.9, 0.16, 1.5, 23.0, false}, c), MappingLoss::kUnmatched);
  // The first reason that applies.
  EXPECT_EQ(mapping_loss({0.75, 0.2, 5.0, 20.0, 90.0, true}, c), MappingLoss::kMismatched);
  MappingLossConfig off;
  off.enabled = false;
  EXPECT_EQ(mapping_loss({0.0, 0.0, 5.0, 20.0, 90.0, true}, off), MappingLoss::kNone);

  LidarMappingResult sweep;
  sweep.gap_s = 5.0;
  sweep.loss = MappingLoss::kJump;  // a rejection is said before the gap
  EXPECT_EQ(mapping_status_name(mapping_status(sweep)), "rejected_jump");
  sweep.loss = MappingLoss::kUnmatched;
  EXPECT_EQ(mapping_status_name(mapping_status(sweep)), "rejected_unmatched");
  sweep.loss = MappingLoss::kMismatched;
  EXPECT_EQ(mapping_status_name(mapping_status(sweep)), "rejected_mismatched");
}

TEST(MappingLoss, ThresholdsOutOfRangeNameTheFile) {
  const auto message = [](const MappingLossConfig& c) {
    try {
      validate_mapping_loss_config(c, "run.yaml");
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_EQ(message(MappingLossConfig{}), "");
  MappingLossConfig c;
  c.min_matched_fraction = 1.5;
  EXPECT_NE(message(c).find("run.yaml"), std::string::npos);
  EXPECT_NE(message(c).find("min_matched_fraction"), std::string::npos);
  c = {};
  c.min_inlier_fraction = -0.1;
  EXPECT_NE(message(c).find("min_inlier_fraction"), std::string::npos);
  c = {};
  c.gap_s = std::nan("");
  EXPECT_NE(message(c).find("gap_s"), std::string::npos);
  c = {};
  c.max_correction_m = 0.0;
  EXPECT_NE(message(c).find("max_correction_m"), std::string::npos);
  c = {};
  c.max_correction_deg = std::nan("");
  EXPECT_NE(message(c).find("max_correction_deg"), std::string::npos);
  c = {};
  c.lost_after_rejected = 0;
  EXPECT_NE(message(c).find("lost_after_rejected"), std::string::npos);
}

}  // namespace
}  // namespace vilslam::lidar
