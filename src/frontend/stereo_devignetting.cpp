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

bool StereoDevignetting::end_round_if_ready() {
  if (!collecting()) return false;
  const bool ready = std::all_of(estimators_.begin(), estimators_.end(), [&](const VignettingEstimator& e) {
    return e.informative_samples() >= samples_per_round_;
  });
  if (!ready) return false;
  // What this round fits is the falloff left in the corrected images: the models multiply, so their k add.
  std::vector<VignettingModel> fitted;
  for (const VignettingEstimator& e : estimators_) fitted.push_back(e.solve());
  if (models_.empty()) models_ = fitted;
  else
    for (std::size_t c = 0; c < models_.size(); ++c) models_[c].k += fitted[c].k;
  gains_ = {devignetting_gain(models_[0], {calib_.cam0.width_px, calib_.cam0.height_px}),
            devignetting_gain(models_[1], {calib_.cam1.width_px, calib_.cam1.height_px})};
  ++rounds_done_;
  estimators_.clear();
  if (!finished()) estimators_ = {VignettingEstimator(calib_.cam0), VignettingEstimator(calib_.cam1)};
  return true;
}

const VignettingModel* StereoDevignetting::model(int camera) const {
  return models_.empty() ? nullptr : &models_.at(camera);
}

}  // namespace vilslam
