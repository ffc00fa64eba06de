#include "frontend/stereo_devignetting.h"

#include <algorithm>

namespace vilslam {

StereoDevignetting::StereoDevignetting(const RigCalibration& calib, int samples_per_round)
    : calib_(calib), samples_per_round_(samples_per_round) {
  if (samples_per_round > 0) estimators_ = {VignettingEstimator(calib.cam0), VignettingEstimator(calib.cam1)};
}

StereoFrame StereoDevignetting::apply(const StereoFrame& pair) const {
  if (gains_.empty()) return pair;
  return {pair.t_ns, devignette(pair.left, gains_[0]), devignette(pair.right, gains_[1])};
}

void StereoDevignetting::add_step(int camera, const cv::Mat& prev, const cv::Mat& cur,
                                  const std::vector<cv::Point2f>& prev_px, const std::vector<cv::Point2f>& cur_px,
                                  const std::vector<bool>& tracked) {
  estimators_.at(camera).add_step(prev, cur, prev_px, cur_px, tracked);
}

StereoDevignetting::RoundEnd StereoDevignetting::end_round_if_ready() {
  if (!collecting()) return RoundEnd::kNone;
  const bool ready = std::all_of(estimators_.begin(), estimators_.end(), [&](const VignettingEstimator& e) {
    return e.informative_samples() >= samples_per_round_;
  });
  if (!ready) return RoundEnd::kNone;
  // What this round fits is the falloff left in the corrected images: the models multiply, so their k add.
  std::vector<VignettingModel> models;
  for (std::size_t c = 0; c < estimators_.size(); ++c) {
    const std::optional<VignettingModel> fitted = estimators_[c].solve();
    if (!fitted) {
      estimators_.clear();
      rejected_ = true;
      return RoundEnd::kRejected;
    }
    models.push_back(*fitted);
    if (!models_.empty()) models[c].k += models_[c].k;
  }
  estimators_.clear();
  const std::vector<cv::Mat> gains = {
      devignetting_gain(models[0], {calib_.cam0.width_px, calib_.cam0.height_px}),
      devignetting_gain(models[1], {calib_.cam1.width_px, calib_.cam1.height_px})};
  for (const cv::Mat& gain : gains) {
    double min_gain = 0, max_gain = 0;
    cv::minMaxLoc(gain, &min_gain, &max_gain);
    if (min_gain < 1 / kMaxAttenuation || max_gain > 1 / kMinAttenuation) {
      rejected_ = true;
      return RoundEnd::kRejected;
    }
  }
  models_ = models;
  gains_ = gains;
  ++rounds_done_;
  if (!finished()) estimators_ = {VignettingEstimator(calib_.cam0), VignettingEstimator(calib_.cam1)};
  return RoundEnd::kFitted;
}

const VignettingModel* StereoDevignetting::model(int camera) const {
  return models_.empty() ? nullptr : &models_.at(camera);
}

}  // namespace vilslam
