#include "sim/camera_render.h"

#include <Eigen/SVD>
#include <opencv2/imgproc.hpp>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <optional>

#include "common/error.h"
#include "sim/camera_rays.h"
#include "sim/material_textures.h"
#include "sim/procedural_noise.h"

namespace vilslam::sim {
namespace {

// Lighting: a fixed soft light from above (half-Lambert term) plus ambient; a sky for rays that miss.
const Vec3 kLightDir_W = Vec3(0.4, 0.25, 0.88).normalized();
constexpr double kAmbient = 0.5;
constexpr double kSkyRadiance = 0.85;
// No paint reflects 95 % of the light: surfaces that bright are light fixtures (lamps, ceiling lights)
// and emit, saturating the pixel at unit gain as real lights do.
constexpr float kEmitterMinGrey = 0.95f;
constexpr float kEmitterRadiance = 1.3f;
// Lens blur (Gaussian PSF sigma in pixels): edges spread over about a pixel as through real optics.
constexpr double kPsfSigmaPx = 0.5;
// Surfaces seen more obliquely than this are filtered as if at this incidence.
constexpr double kMinCosIncidence = 0.15;

struct PoseSample {
  Eigen::Matrix3f R_W_C;
  Vec3 origin_W;
};

// Anisotropic filtering: the texture lookup of pixel i (at row, col) averaged along the long axis of its
// footprint in surface coordinates. The footprint is the parallelogram spanned by the uv steps to the hits of
// the next pixel along the row and along the column (the previous one at the border); the level follows its
// short axis and at most `samples` lookups spread over its long one (the EWA idea with a box along the axis).
// Where a neighbour's ray leaves the face (no hit, another material or a normal over 2.6 deg off) the
// footprint is unknown and the isotropic lookup at `isotropic_footprint_m` stays.
float anisotropic_albedo(const MaterialTextures& textures, const RayTable& rays,
                         const std::vector<std::optional<RayHit>>& hits, int row, int col, int samples,
                         double isotropic_footprint_m) {
  const RayHit& hit = *hits[static_cast<std::size_t>(row) * rays.width + col];
  const auto uv_step_to = [&](int r, int c) -> std::optional<Eigen::Vector2d> {
    const std::optional<RayHit>& h = hits[static_cast<std::size_t>(r) * rays.width + c];
    if (!h || h->material != hit.material || h->normal_W.dot(hit.normal_W) < 0.999) return std::nullopt;
    return h->uv_m - hit.uv_m;
  };
  const std::optional<Eigen::Vector2d> along_row = uv_step_to(row, col + 1 < rays.width ? col + 1 : col - 1);
  const std::optional<Eigen::Vector2d> along_col = uv_step_to(row + 1 < rays.height ? row + 1 : row - 1, col);
  if (!along_row || !along_col) return textures.albedo(hit.material, hit.uv_m, isotropic_footprint_m);
  Eigen::Matrix2d footprint;
  footprint << *along_row, *along_col;
  const Eigen::JacobiSVD<Eigen::Matrix2d> svd(footprint, Eigen::ComputeFullU);
  const double long_m = svd.singularValues()(0), short_m = svd.singularValues()(1);
  if (!(short_m > 0)) return textures.albedo(hit.material, hit.uv_m, isotropic_footprint_m);
  const int n = std::clamp(static_cast<int>(std::lround(long_m / short_m)), 1, samples);
  const Eigen::Vector2d long_axis_m = svd.matrixU().col(0) * long_m;
  const double level_footprint_m = std::max(short_m, long_m / n);
  double sum = 0;
  for (int k = 0; k < n; ++k)
    sum += textures.albedo(hit.material, hit.uv_m + long_axis_m * ((k + 0.5) / n - 0.5), level_footprint_m);
  return static_cast<float>(sum / n);
}

// Radiance (0..1) of every pixel seen from one pose; z_C of the hit when depth is wanted. With anisotropic
// filtering every pixel's ray is cast first, so that the filter can read its neighbours' hits.
void trace(const World& world, const MaterialTextures& textures, const RayTable& rays, const PoseSample& pose,
           double max_range_m, int anisotropic_samples, float weight, cv::Mat& radiance, cv::Mat* depth) {
  std::vector<bool> emitter;
  for (const Material& m : world.materials()) emitter.push_back(m.base_grey >= kEmitterMinGrey);
  const auto direction_W = [&](std::size_t i) { return (pose.R_W_C * rays.dir_C[i]).cast<double>().normalized(); };
  std::vector<std::optional<RayHit>> hits;
  if (anisotropic_samples > 1) {
    hits.resize(static_cast<std::size_t>(rays.width) * rays.height);
    tbb::parallel_for(0, rays.height, [&](int r) {
      for (int c = 0; c < rays.width; ++c) {
        const std::size_t i = static_cast<std::size_t>(r) * rays.width + c;
        hits[i] = world.raycast(pose.origin_W, direction_W(i), max_range_m);
      }
    });
  }
  tbb::parallel_for(0, rays.height, [&](int r) {
    float* out = radiance.ptr<float>(r);
    float* z_out = depth ? depth->ptr<float>(r) : nullptr;
    for (int c = 0; c < rays.width; ++c) {
      const std::size_t i = static_cast<std::size_t>(r) * rays.width + c;
      const Vec3 d_W = direction_W(i);
      const std::optional<RayHit> hit = hits.empty() ? world.raycast(pose.origin_W, d_W, max_range_m) : hits[i];
      if (!hit) {
        out[c] += weight * static_cast<float>(kSkyRadiance * (0.9 + 0.1 * std::max(0.0, d_W.z())));
        if (z_out) z_out[c] = 0;
        continue;
      }
      if (z_out) z_out[c] = static_cast<float>(hit->range_m * rays.dir_C[i].z());
      if (emitter[hit->material]) {
        out[c] += weight * kEmitterRadiance;
        continue;
      }
      const double cos_incidence = std::max(kMinCosIncidence, std::abs(hit->normal_W.dot(d_W)));
      const double footprint_m = hit->range_m * rays.pixel_angle_rad[i] / cos_incidence;
      const float albedo = anisotropic_samples > 1
                               ? anisotropic_albedo(textures, rays, hits, r, c, anisotropic_samples, footprint_m)
                               : textures.albedo(hit->material, hit->uv_m, footprint_m);
      const double shade = kAmbient + (1 - kAmbient) * (0.5 + 0.5 * hit->normal_W.dot(kLightDir_W));
      out[c] += weight * static_cast<float>(albedo * shade);
    }
  });
}

// Standard normal quantiles at (k + 0.5) / 2^16 (inverse CDF by Newton on erfc), for table sampling.
const std::vector<float>& normal_quantiles() {
  static const std::vector<float> table = [] {
    std::vector<float> q(1 << 16);
    for (std::size_t k = 0; k < q.size(); ++k) {
      const double p = (k + 0.5) / q.size();
      double x = 0;
      for (int it = 0; it < 60; ++it) {
        const double cdf = 0.5 * std::erfc(-x / std::sqrt(2.0));
        x -= (cdf - p) / (std::exp(-0.5 * x * x) / std::sqrt(2 * M_PI));
      }
      q[k] = static_cast<float>(x);
    }
    return q;
  }();
  return table;
}

// Standard normal deviate of pixel i: a counter-based hash of (seed, i) picks a quantile.
float pixel_noise(const std::vector<float>& quantiles, std::uint64_t seed, std::int64_t i) {
  return quantiles[hash64(seed, i) >> 48];
}

}  // namespace

cv::Mat render_image(const World& world, const CameraIntrinsics& intrinsics,
                     const std::function<SE3(TimeNs)>& T_W_C, TimeNs t_ns, const RenderOptions& options,
                     cv::Mat* depth_m) {
  if (options.motion_blur_samples < 1 || options.anisotropic_samples < 1 || !(options.exposure_time_s >= 0) ||
      !std::isfinite(options.exposure_gain) || !(options.noise_sigma_grey >= 0) ||
      !(options.vignetting >= 0 && options.vignetting <= 1))
    throw InputError("render options",
                     "motion_blur_samples >= 1, anisotropic_samples >= 1, exposure_time_s >= 0, finite gain and noise, "
                     "vignetting in [0, 1] needed");
  const std::shared_ptr<const RayTable> rays = ray_table(intrinsics);
  const std::shared_ptr<const MaterialTextures> textures = material_textures(world.materials());
  const double max_range_m = world.bounds().diagonal().norm() + 1.0;
  const int n = options.motion_blur_samples;
  const TimeNs exposure_ns = s_to_ns(options.exposure_time_s);

  cv::Mat radiance = cv::Mat::zeros(intrinsics.height_px, intrinsics.width_px, CV_32F);
  if (depth_m) *depth_m = cv::Mat::zeros(intrinsics.height_px, intrinsics.width_px, CV_32F);
  for (int k = 0; k < n; ++k) {
    // Sample k at the centre of the k-th of n equal slices of the exposure; odd n has one at t_ns.
    const TimeNs t_k = n == 1 ? t_ns : t_ns - exposure_ns / 2 + (exposure_ns * (2 * k + 1)) / (2 * n);
    const SE3 T = T_W_C(t_k);
    const bool depth_here = depth_m && t_k == t_ns;
    trace(world, *textures, *rays, {T.rotation().cast<float>(), T.translation()}, max_range_m,
          options.anisotropic_samples, 1.0f / n, radiance, depth_here ? depth_m : nullptr);
  }
  if (depth_m && n % 2 == 0) {
    const SE3 T = T_W_C(t_ns);
    cv::Mat unused = cv::Mat::zeros(radiance.size(), CV_32F);
    trace(world, *textures, *rays, {T.rotation().cast<float>(), T.translation()}, max_range_m, 1, 0.0f, unused,
          depth_m);
  }
  cv::GaussianBlur(radiance, radiance, cv::Size(5, 5), kPsfSigmaPx, kPsfSigmaPx, cv::BORDER_REFLECT);

  cv::Mat image(radiance.size(), CV_8U);
  const double scale = 255.0 * options.exposure_gain;
  const std::vector<float>& quantiles = normal_quantiles();
  tbb::parallel_for(0, image.rows, [&](int r) {
    const float* in = radiance.ptr<float>(r);
    std::uint8_t* out = image.ptr<std::uint8_t>(r);
    for (int c = 0; c < image.cols; ++c) {
      const std::int64_t i = static_cast<std::int64_t>(r) * image.cols + c;
      const double cos2 = static_cast<double>(rays->dir_C[i].z()) * rays->dir_C[i].z();
      const double vignette = 1.0 - options.vignetting * (1.0 - cos2 * cos2);
      const double v = scale * vignette * in[c] + options.noise_sigma_grey * pixel_noise(quantiles, options.noise_seed, i);
      out[c] = static_cast<std::uint8_t>(std::clamp(std::lround(v), 0L, 255L));
    }
  });
  return image;
}

}  // namespace vilslam::sim
