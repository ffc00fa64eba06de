#include "lidar/mapping_loss.h"

#include <cmath>

#include "common/error.h"

namespace vilslam::lidar {

MappingLoss mapping_loss(const SweepFit& fit, const MappingLossConfig& c) {
  if (!c.enabled) return MappingLoss::kNone;
  if (fit.matched_fraction > 0.0 && fit.inlier_fraction < c.min_inlier_fraction) return MappingLoss::kMismatched;
  if (fit.gap_s > c.gap_s && fit.matched_fraction < c.min_matched_fraction) return MappingLoss::kUnmatched;
  if (fit.prior_aided && (fit.correction_m > c.max_correction_m || fit.correction_deg > c.max_correction_deg)) {
    return MappingLoss::kJump;
  }
  return MappingLoss::kNone;
}

void validate_mapping_loss_config(const MappingLossConfig& c, const std::string& source) {
  if (!(c.min_inlier_fraction >= 0.0 && c.min_inlier_fraction <= 1.0)) {
    throw InputError(source, "'lidar_mapper.loss.min_inlier_fraction' must be in [0, 1]");
  }
  if (!(c.min_matched_fraction >= 0.0 && c.min_matched_fraction <= 1.0)) {
    throw InputError(source, "'lidar_mapper.loss.min_matched_fraction' must be in [0, 1]");
  }
  if (!(c.gap_s >= 0.0) || !std::isfinite(c.gap_s)) throw InputError(source, "'lidar_mapper.loss.gap_s' must be >= 0");
  if (!(c.max_correction_m > 0.0) || !std::isfinite(c.max_correction_m)) {
    throw InputError(source, "'lidar_mapper.loss.max_correction_m' must be positive and finite");
  }
  if (!(c.max_correction_deg > 0.0 && c.max_correction_deg <= 180.0)) {
    throw InputError(source, "'lidar_mapper.loss.max_correction_deg' must be in (0, 180]");
  }
  if (c.lost_after_rejected < 1) throw InputError(source, "'lidar_mapper.loss.lost_after_rejected' must be at least 1");
}

}  // namespace vilslam::lidar
