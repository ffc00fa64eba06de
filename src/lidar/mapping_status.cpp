#include "lidar/mapping_status.h"

namespace vilslam::lidar {

MappingStatus mapping_status(const LidarMappingResult& sweep, const MappingStatusThresholds& thresholds) {
  if (sweep.loss == MappingLoss::kMismatched) return MappingStatus::kRejectedMismatched;
  if (sweep.loss == MappingLoss::kUnmatched) return MappingStatus::kRejectedUnmatched;
  if (sweep.loss == MappingLoss::kJump) return MappingStatus::kRejectedJump;
  if (sweep.reanchored) return MappingStatus::kReanchored;
  if (sweep.gap_s > thresholds.gap_s) return MappingStatus::kAfterGap;
  if (!sweep.converged) return MappingStatus::kNotConverged;
  if (sweep.correction_m > thresholds.correction_m || sweep.correction_deg > thresholds.correction_deg) {
    return MappingStatus::kPredictionContradicted;
  }
  if (sweep.degenerate) return MappingStatus::kDegenerate;
  return MappingStatus::kOk;
}

std::string mapping_status_name(MappingStatus status) {
  switch (status) {
    case MappingStatus::kOk: return "ok";
    case MappingStatus::kReanchored: return "reanchored";
    case MappingStatus::kDegenerate: return "degenerate";
    case MappingStatus::kAfterGap: return "after_gap";
    case MappingStatus::kNotConverged: return "not_converged";
    case MappingStatus::kPredictionContradicted: return "prediction_contradicted";
    case MappingStatus::kRejectedMismatched: return "rejected_mismatched";
    case MappingStatus::kRejectedUnmatched: return "rejected_unmatched";
    case MappingStatus::kRejectedJump: return "rejected_jump";
  }
  return {};
}

}  // namespace vilslam::lidar
