#pragma once
// The vignetting self-calibration of both cameras as the frontend runs it (FrontendConfig::vignetting_samples,
// docs/frontend.md "Vignetting self-calibration"). It works in rounds: each round collects KLT brightness
// samples on the images as corrected so far and fits what is left of the falloff; the rounds' fits multiply.
// A later round is needed because the KLT, which has no brightness model, itself absorbs part of a brightness
// change by moving the track, so the first fit comes out about a tenth too weak; on corrected images little
// brightness change is left to absorb.
#include <opencv2/core.hpp>
#include <optional>
#include <vector>

#include "common/calibration.h"
#include "common/types.h"
#include "frontend/vignetting.h"

namespace vilslam {

class StereoDevignetting {
 public:
  static constexpr int kRounds = 3;

  // samples_per_round 0: off (apply() returns the pair unchanged, nothing is collected).
  StereoDevignetting(const RigCalibration& calib, int samples_per_round);

  // The pair with the current correction (the pair itself before the first round ends).
  StereoFrame apply(const StereoFrame& pair) const;

  bool collecting() const { return !estimators_.empty(); }
  // KLT steps of camera 0 or 1 between the previous and this corrected image (VignettingEstimator::add_step).
  void add_step(int camera, const cv::Mat& prev, const cv::Mat& cur, const std::vector<cv::Point2f>& prev_px,
                const std::vector<cv::Point2f>& cur_px, const std::vector<bool>& tracked);
  enum class RoundEnd { kNone, kFitted, kRejected };
  // Ends the round when both cameras have samples_per_round informative samples. kFitted: the correction
  // changed (the caller then corrects the current pair again). kRejected: no fit (the samples do not constrain
  // it), or one that would leave some pixel darker than kMinAttenuation or brighter than kMaxAttenuation times
  // the centre, which no lens does (moving lights, a scene that is not static): the self-calibration stops, the
  // rounds before stay.
  RoundEnd end_round_if_ready();

  static constexpr double kMinAttenuation = 0.2, kMaxAttenuation = 1.1;

  // The correction so far for camera 0 or 1; nullptr before the first round ends.
  const VignettingModel* model(int camera) const;
  // True once the last round has ended or a fit was rejected.
  bool finished() const { return rounds_done_ == kRounds || rejected_; }

 private:
  RigCalibration calib_;
  int samples_per_round_ = 0;
  int rounds_done_ = 0;
  bool rejected_ = false;
  std::vector<VignettingEstimator> estimators_;  // of the running round, both cameras
  std::vector<VignettingModel> models_;
  std::vector<cv::Mat> gains_;
};

}  // namespace vilslam
