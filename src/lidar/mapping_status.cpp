#include "lidar/mapping_status.h"

namespace vilslam::lidar {

MappingStatus mapping_status(const LidarMappingResult& sweep, const MappingStatusThresholds& thresholds) {
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
    case MappingStatus::kDegenerate: return "degenerate";
    case MappingStatus::kAfterGap: return "after_gap";
    case MappingStatus::kNotConverged: return "not_converged";
    case MappingStatus::kPredictionContradicted: return "prediction_contradicted";
  }
  return {};
}

}  // namespace vilslam::lidar
