#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <map>

#include "frontend/frontend.h"
#include "frontend/stereo_devignetting.h"
#include "frontend/vignetting.h"
#include "synthetic_stereo.h"

namespace vilslam {
namespace {

// The simulator's falloff (src/sim/camera_render.cpp): 1 - a (1 - cos^4) of the angle off the optical axis.
double true_attenuation(const CameraIntrinsics& cam, double u, double v, double amount = 0.5) {
  const double rho = std::pow((u - cam.cx) / cam.fx, 2) + std::pow((v - cam.cy) / cam.fy, 2);
  const double cos2 = 1.0 / (1.0 + rho);
  return 1.0 - amount * (1.0 - cos2 * cos2);
}

// The image as a lens vignetting by `amount` at this exposure makes it.
cv::Mat vignetted(const cv::Mat& image, const CameraIntrinsics& cam, double exposure, double amount = 0.5) {
  cv::Mat out(image.size(), CV_8U);
  for (int v = 0; v < image.rows; ++v) {
    for (int u = 0; u < image.cols; ++u) {
      const double grey = image.at<uchar>(v, u) * exposure * true_attenuation(cam, u, v, amount);
      out.at<uchar>(v, u) = cv::saturate_cast<uchar>(grey);
    }
  }
  return out;
}

// Exposure of pair k: steps up to `amplitude` from pair to pair.
double exposure(int k, double amplitude = 0.08) { return 1.0 + amplitude * std::sin(0.9 * k); }

// A plane of mid-grey texture (no clipped pixels) 3 m ahead; the camera pans and tilts across it, so the
// plane's points sweep through the image's centre and corners.
struct PanningScene {
  CameraIntrinsics cam = test::pinhole_752x480();
  test::TexturedPlane plane = [] {
    test::TexturedPlane p = test::facing_plane(3.0, 0.0, 5);
    p.texture.convertTo(p.texture, CV_8U, 0.6, 50);  // grey 50 .. 203
    return p;
  }();
  SE3 T_W_C(int k) const { return SE3(so3::exp(Vec3(0.012 * std::sin(0.2 * k), 0.018 * (k - 12), 0)), Vec3(0, 0, 0)); }
  cv::Mat image(int k, double amount = 0.5) const {
    return vignetted(test::render_plane(plane, cam, T_W_C(k)), cam, exposure(k), amount);
  }
};

// One frame step of the panning scene with exact correspondences: a grid of pixels of image k - 1 through the
// plane into image k.
struct ExactStep {
  cv::Mat prev, cur;
  std::vector<cv::Point2f> prev_px, cur_px;
  std::vector<bool> tracked;
};

ExactStep exact_step(const PanningScene& scene, int k, double amount = 0.5) {
  ExactStep step{scene.image(k - 1, amount), scene.image(k, amount), {}, {}, {}};
  for (int v = 20; v < scene.cam.height_px - 20; v += 15) {
    for (int u = 20; u < scene.cam.width_px - 20; u += 15) {
      const Eigen::Vector2d xy((u - scene.cam.cx) / scene.cam.fx, (v - scene.cam.cy) / scene.cam.fy);
      const Vec3 p_W = scene.T_W_C(k - 1) * scene.plane.intersect(scene.T_W_C(k - 1), xy);
      const Vec3 p_C = scene.T_W_C(k).inverse() * p_W;
      step.prev_px.emplace_back(u, v);
      step.cur_px.emplace_back(scene.cam.fx * p_C.x() / p_C.z() + scene.cam.cx,
                               scene.cam.fy * p_C.y() / p_C.z() + scene.cam.cy);
      step.tracked.push_back(true);
    }
  }
  return step;
}

TEST(Vignetting, SelfCalibrationRecoversTheFalloffUnderExposureChanges) {
  const PanningScene scene;
  VignettingEstimator estimator(scene.cam);
  for (int k = 1; k < 25; ++k) {
    const ExactStep step = exact_step(scene, k);
    estimator.add_step(step.prev, step.cur, step.prev_px, step.cur_px, step.tracked);
  }
  ASSERT_GT(estimator.informative_samples(), 5000);
  const VignettingModel model = estimator.solve().value();
  double worst = 0;
  for (int v = 0; v < scene.cam.height_px; v += 8) {
    for (int u = 0; u < scene.cam.width_px; u += 8) {
      worst = std::max(worst, std::abs(model.attenuation(u, v) / true_attenuation(scene.cam, u, v) - 1));
    }
  }
  std::printf("fitted falloff: worst relative error %.4f over the image (corner truth %.3f, fit %.3f)\n", worst,
              true_attenuation(scene.cam, 0, 0), model.attenuation(0, 0));
  EXPECT_LT(worst, 0.01);
}

TEST(Vignetting, DevignettingFlattensAUniformSurface) {
  const CameraIntrinsics cam = test::pinhole_752x480();
  const cv::Mat flat(cam.height_px, cam.width_px, CV_8U, cv::Scalar(180));
  // The cubic nearest to the simulator's falloff at 0.5 (least squares over rho in [0, 1]).
  VignettingModel truth_fit = VignettingModel::flat(cam);
  truth_fit.k = Eigen::Vector3d(-0.9645, 0.7545, -0.2624);
  const cv::Mat corrected = devignette(vignetted(flat, cam, 1.0), devignetting_gain(truth_fit, flat.size()));
  double lo = 0, hi = 0;
  cv::minMaxLoc(corrected, &lo, &hi);
  EXPECT_GE(lo, 179);
  EXPECT_LE(hi, 181);
  EXPECT_EQ(corrected.at<uchar>(240, 376), 180);
}

TEST(Vignetting, TracksWithoutRadialMotionAreRejected) {
  const PanningScene scene;
  VignettingEstimator estimator(scene.cam);
  const std::vector<cv::Point2f> px = {{300, 200}, {400, 300}};
  estimator.add_step(scene.image(0), scene.image(0), px, px, {true, true});
  EXPECT_EQ(estimator.informative_samples(), 0);
  EXPECT_FALSE(estimator.solve().has_value());
}

// A lens brightening its edges (the same falloff with the opposite sign, 1.75 at the corners) is no lens: the
// round's fit is rejected and nothing is corrected; the true falloff on the same steps is taken.
TEST(Vignetting, ImplausibleFitStopsTheSelfCalibration) {
  const PanningScene scene;
  const RigCalibration calib = test::pinhole_stereo_rig();
  for (const double amount : {-1.0, 0.5}) {
    StereoDevignetting devignetting(calib, 2000);
    StereoDevignetting::RoundEnd end = StereoDevignetting::RoundEnd::kNone;
    for (int k = 1; k < 25 && end == StereoDevignetting::RoundEnd::kNone; ++k) {
      const ExactStep step = exact_step(scene, k, amount);
      for (int camera = 0; camera < 2; ++camera) {
        devignetting.add_step(camera, step.prev, step.cur, step.prev_px, step.cur_px, step.tracked);
      }
      end = devignetting.end_round_if_ready();
    }
    if (amount < 0) {
      EXPECT_EQ(end, StereoDevignetting::RoundEnd::kRejected);
      EXPECT_EQ(devignetting.model(0), nullptr);
      EXPECT_TRUE(devignetting.finished());
      EXPECT_FALSE(devignetting.collecting());
      const StereoFrame pair{1, scene.image(3, amount), scene.image(4, amount)};
      EXPECT_EQ(devignetting.apply(pair).left.data, pair.left.data);  // untouched
    } else {
      EXPECT_EQ(end, StereoDevignetting::RoundEnd::kFitted);
      ASSERT_NE(devignetting.model(0), nullptr);
      EXPECT_NEAR(devignetting.model(0)->attenuation(0, 0), true_attenuation(calib.cam0, 0, 0), 0.01);
      EXPECT_TRUE(devignetting.collecting());  // the next round
    }
  }
}

// The frontend on a vignetted stereo sequence: once it has fitted the falloff (3 rounds of 2000 samples,
// done by pair 20), its KLT tracks stay as near the true image of the point they started on as on the same
// sequence without vignetting, and nearer than without the correction.
TEST(Vignetting, FrontendSelfCalibrationKeepsTracksOnTheirPoint) {
  const PanningScene scene;
  const RigCalibration calib = test::pinhole_stereo_rig();
  const auto drift_px = [&](bool vignetting, int samples, VignettingModel* fitted) -> double {
    FrontendConfig config;
    config.vignetting_samples = samples;
    config.min_tracked_matches = 100;
    Frontend frontend(calib, config);
    const auto lens = [&](const cv::Mat& image, const CameraIntrinsics& cam, int k) {
      return vignetted(image, cam, exposure(k, 0.005), vignetting ? 0.5 : 0.0);
    };
    std::map<std::uint64_t, Vec3> first_W;  // track id -> the plane point it started on
    double sum_px = 0;
    int n = 0, fitted_at = -1;
    for (int k = 0; k < 45; ++k) {
      StereoFrame f;
      f.t_ns = 1'000'000'000 + k * 50'000'000LL;
      f.left = lens(test::render_plane(scene.plane, calib.cam0, scene.T_W_C(k)), calib.cam0, k);
      f.right = lens(test::render_plane(scene.plane, calib.cam1, scene.T_W_C(k) * calib.T_C0_C1()), calib.cam1, k);
      const FrontendOutput out = frontend.process(f);
      if (frontend.last_stats().vignetting_fitted) fitted_at = k;
      for (const StereoMatch& m : out.matches) {
        const Vec3 p_W = scene.T_W_C(k) * scene.plane.intersect(scene.T_W_C(k), m.left_norm);
        if (k >= 20) first_W.emplace(m.track_id, p_W);  // tracks of the corrected images only
        const auto it = first_W.find(m.track_id);
        if (it == first_W.end()) continue;
        Eigen::Vector2d px;
        if (!frontend.rig().cam0.project(scene.T_W_C(k).inverse() * it->second, &px)) continue;
        sum_px += (px - m.left_px).norm();
        ++n;
      }
    }
    if (fitted) {
      EXPECT_GE(fitted_at, 1);
      EXPECT_LT(fitted_at, 20);
      EXPECT_NE(frontend.vignetting(0), nullptr);
      if (frontend.vignetting(0)) *fitted = *frontend.vignetting(0);
    }
    EXPECT_GT(n, 1000);
    return sum_px / n;
  };
  VignettingModel model;
  const double ideal = drift_px(false, 0, nullptr), without = drift_px(true, 0, nullptr),
               with = drift_px(true, 2000, &model);
  std::printf("mean distance of a track from its point's true pixel: %.3f px without vignetting; vignetted %.3f px "
              "uncorrected, %.3f px corrected; fitted corner brightness %.3f (truth %.3f)\n",
              ideal, without, with, model.attenuation(0, 0), true_attenuation(calib.cam0, 0, 0));
  EXPECT_LT(with, 0.7 * without);
  EXPECT_LT(with, 1.15 * ideal);
  EXPECT_NEAR(model.attenuation(0, 0), true_attenuation(calib.cam0, 0, 0), 0.02);
}

}  // namespace
}  // namespace vilslam
