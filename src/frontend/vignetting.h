#pragma once
// Photometric self-calibration of a lens's vignetting from the frontend's own KLT tracks, and its
// correction (docs/frontend.md, "Vignetting self-calibration").
//
// A point tracked from one frame to the next keeps its radiance; what changes its brightness is the
// exposure (the same for the whole image) and the vignetting at its two pixels. With the falloff modelled
// as V(rho) = exp(k1 rho + k2 rho^2 + k3 rho^3), rho the squared distance from the principal point in focal
// lengths, the log ratio of a tracked patch's mean brightness is
//   log(b_cur / b_prev) = k . (f(rho_cur) - f(rho_prev)) + (log e_cur - log e_prev),  f(rho) = (rho, rho^2, rho^3),
// linear in k with one unknown exposure step per frame pair, which the fit removes by centring each frame's
// samples (weighted, with Huber weights against occlusions and glints).
#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <optional>
#include <vector>

#include "common/calibration.h"

namespace vilslam {

struct VignettingModel {
  double fx = 1, fy = 1, cx = 0, cy = 0;  // the camera's pinhole part (pixels)
  Eigen::Vector3d k = Eigen::Vector3d::Zero();

  // No falloff yet, on this camera's pinhole.
  static VignettingModel flat(const CameraIntrinsics& camera);

  // Squared distance of pixel (u, v) from the principal point, in focal lengths.
  double rho(double u_px, double v_px) const;
  // V at pixel (u, v): 1 at the principal point.
  double attenuation(double u_px, double v_px) const;
};

// 1 / V for every pixel of an image of `size` (CV_32F).
cv::Mat devignetting_gain(const VignettingModel& model, const cv::Size& size);

// image (8-bit grey) times gain, rounded and saturated to 8 bits.
cv::Mat devignette(const cv::Mat& image, const cv::Mat& gain);

class VignettingEstimator {
 public:
  explicit VignettingEstimator(const CameraIntrinsics& camera);

  // One frame step of one camera: points tracked from prev_px in `prev` to cur_px in `cur` (8-bit grey,
  // uncorrected); tracked[i] false skips point i. Patches near the border or with clipped pixels are skipped.
  void add_step(const cv::Mat& prev, const cv::Mat& cur, const std::vector<cv::Point2f>& prev_px,
                const std::vector<cv::Point2f>& cur_px, const std::vector<bool>& tracked);

  // Samples whose rho changed enough to say something about the falloff (|d rho| >= kMinRhoStep).
  int informative_samples() const { return informative_; }

  // The robust least-squares fit over every sample so far; nullopt when they do not constrain the falloff.
  std::optional<VignettingModel> solve() const;

  static constexpr double kMinRhoStep = 1e-3;
  static constexpr int kPatchPx = 21;  // side of the square patch whose weighted mean brightness is compared

 private:
  struct Sample {
    int step = 0;           // which frame step (one exposure change each)
    Eigen::Vector3d df;     // f(rho_cur) - f(rho_prev)
    double log_ratio = 0;   // log(b_cur / b_prev)
  };
  bool patch_mean(const cv::Mat& image, const cv::Point2f& px, double* mean) const;

  VignettingModel pinhole_;
  std::vector<Sample> samples_;
  int steps_ = 0;
  int informative_ = 0;
};

}  // namespace vilslam
