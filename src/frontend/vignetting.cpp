#include "frontend/vignetting.h"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>

namespace vilslam {
namespace {

Eigen::Vector3d powers(double rho) { return {rho, rho * rho, rho * rho * rho}; }

// Median of |r| / 0.6745: the residuals' standard deviation, robust to the outliers.
double robust_sigma(std::vector<double> abs_residuals) {  // a copy: nth_element reorders
  if (abs_residuals.empty()) return 0;
  const auto mid = abs_residuals.begin() + abs_residuals.size() / 2;
  std::nth_element(abs_residuals.begin(), mid, abs_residuals.end());
  return *mid / 0.6745;
}

constexpr int kIterations = 8;
constexpr double kHuberSigmas = 1.345;
// Patches with a pixel at or beyond these grey levels are clipped and say nothing about the falloff.
constexpr float kDarkestGrey = 4, kBrightestGrey = 251;

}  // namespace

VignettingModel VignettingModel::flat(const CameraIntrinsics& camera) {
  VignettingModel model;
  model.fx = camera.fx;
  model.fy = camera.fy;
  model.cx = camera.cx;
  model.cy = camera.cy;
  return model;
}

double VignettingModel::rho(double u_px, double v_px) const {
  const double x = (u_px - cx) / fx, y = (v_px - cy) / fy;
  return x * x + y * y;
}

double VignettingModel::attenuation(double u_px, double v_px) const { return std::exp(k.dot(powers(rho(u_px, v_px)))); }

cv::Mat devignetting_gain(const VignettingModel& model, const cv::Size& size) {
  cv::Mat gain(size, CV_32F);
  for (int v = 0; v < size.height; ++v) {
    float* row = gain.ptr<float>(v);
    for (int u = 0; u < size.width; ++u) row[u] = static_cast<float>(1.0 / model.attenuation(u, v));
  }
  return gain;
}

cv::Mat devignette(const cv::Mat& image, const cv::Mat& gain) {
  cv::Mat corrected;
  cv::multiply(image, gain, corrected, 1.0, CV_8U);  // rounds and saturates
  return corrected;
}

VignettingEstimator::VignettingEstimator(const CameraIntrinsics& camera) : pinhole_(VignettingModel::flat(camera)) {}

bool VignettingEstimator::patch_mean(const cv::Mat& image, const cv::Point2f& px, double* mean) const {
  // A Gaussian weight (sigma a sixth of the side) rather than a plain mean: a track a little off its point
  // moves structure across the patch's soft edge, not across a hard one, so the brightness hardly changes.
  static const cv::Mat weights = [] {
    const cv::Mat g = cv::getGaussianKernel(kPatchPx, kPatchPx / 6.0, CV_32F);
    return cv::Mat(g * g.t());
  }();
  const float half = 0.5f * kPatchPx + 1;
  if (px.x < half || px.y < half || px.x > image.cols - 1 - half || px.y > image.rows - 1 - half) return false;
  cv::Mat patch;
  cv::getRectSubPix(image, cv::Size(kPatchPx, kPatchPx), px, patch, CV_32F);
  double lo = 0, hi = 0;
  cv::minMaxLoc(patch, &lo, &hi);
  if (lo <= kDarkestGrey || hi >= kBrightestGrey) return false;
  *mean = patch.dot(weights);
  return true;
}

void VignettingEstimator::add_step(const cv::Mat& prev, const cv::Mat& cur, const std::vector<cv::Point2f>& prev_px,
                                   const std::vector<cv::Point2f>& cur_px, const std::vector<bool>& tracked) {
  for (std::size_t i = 0; i < prev_px.size(); ++i) {
    if (!tracked[i]) continue;
    double b_prev = 0, b_cur = 0;
    if (!patch_mean(prev, prev_px[i], &b_prev) || !patch_mean(cur, cur_px[i], &b_cur)) continue;
    const double rho_prev = pinhole_.rho(prev_px[i].x, prev_px[i].y), rho_cur = pinhole_.rho(cur_px[i].x, cur_px[i].y);
    samples_.push_back({steps_, powers(rho_cur) - powers(rho_prev), std::log(b_cur / b_prev)});
    informative_ += std::abs(rho_cur - rho_prev) >= kMinRhoStep;
  }
  ++steps_;
}

std::optional<VignettingModel> VignettingEstimator::solve() const {
  VignettingModel model = pinhole_;
  std::vector<double> weight(samples_.size(), 1.0), abs_residual(samples_.size(), 0.0);
  for (int iteration = 0; iteration < kIterations; ++iteration) {
    // Weighted centring per frame step removes its exposure change (Frisch-Waugh): the exact weighted
    // least-squares k for these weights.
    struct Sums {
      double w = 0, y = 0;
      Eigen::Vector3d x = Eigen::Vector3d::Zero();
    };
    std::vector<Sums> per_step(steps_);
    for (std::size_t i = 0; i < samples_.size(); ++i) {
      Sums& s = per_step[samples_[i].step];
      s.w += weight[i];
      s.y += weight[i] * samples_[i].log_ratio;
      s.x += weight[i] * samples_[i].df;
    }
    Eigen::Matrix3d normal = Eigen::Matrix3d::Zero();
    Eigen::Vector3d rhs = Eigen::Vector3d::Zero();
    for (std::size_t i = 0; i < samples_.size(); ++i) {
      const Sums& s = per_step[samples_[i].step];
      const Eigen::Vector3d x = samples_[i].df - s.x / s.w;
      const double y = samples_[i].log_ratio - s.y / s.w;
      normal += weight[i] * x * x.transpose();
      rhs += weight[i] * x * y;
    }
    const Eigen::LDLT<Eigen::Matrix3d> ldlt(normal);
    if (ldlt.info() != Eigen::Success || !ldlt.isPositive() || normal.trace() <= 0) return std::nullopt;
    model.k = ldlt.solve(rhs);
    for (std::size_t i = 0; i < samples_.size(); ++i) {
      const Sums& s = per_step[samples_[i].step];
      abs_residual[i] = std::abs(samples_[i].log_ratio - s.y / s.w - (samples_[i].df - s.x / s.w).dot(model.k));
    }
    const double threshold = kHuberSigmas * robust_sigma(abs_residual);
    for (std::size_t i = 0; i < samples_.size(); ++i) {
      weight[i] = abs_residual[i] <= threshold ? 1.0 : threshold / abs_residual[i];
    }
  }
  return model;
}

}  // namespace vilslam
