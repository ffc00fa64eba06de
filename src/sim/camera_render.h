#pragma once
// Stereo rendering by ray casting the world with its textures.
#include <functional>
#include <opencv2/core.hpp>

#include "common/calibration.h"
#include "common/lie.h"
#include "common/time.h"
#include "sim/world.h"

namespace vilslam::sim {

struct RenderOptions {
  double noise_sigma_grey = 2.0;  // additive Gaussian pixel noise, grey levels (0..255)
  double exposure_gain = 1.0;     // multiplies radiance before quantization (exposure changes)
  int motion_blur_samples = 1;    // > 1: average of that many poses over the exposure time
  // > 1: anisotropic texture filtering. The texture level follows the short axis of the pixel's footprint
  // and up to that many lookups are averaged along its long axis, as a lens integrates a surface seen at a
  // grazing angle; 1 filters by the long axis alone, which also blurs such a surface across (docs/sim_camera.md).
  int anisotropic_samples = 1;
  double exposure_time_s = 0.005;
  // Share of the lens's natural cos^4 fall-off applied: brightness (1 - v) + v cos^4(angle off the optical
  // axis), so v = 0.5 leaves the simulator's camera's corners (44 deg off axis) at 0.64 of the centre.
  double vignetting = 0.0;
  std::uint64_t noise_seed = 0;   // the frame's noise is a pure function of this seed
};

// Renders an 8-bit grey image of the camera `intrinsics` (with its distortion) at pose T_W_C(t) for
// t in [t_ns - exposure/2, t_ns + exposure/2] (only t_ns when motion_blur_samples == 1).
// When depth_m is given it receives the range along the optical axis (z_C) of each pixel, 0 for no hit.
cv::Mat render_image(const World& world, const CameraIntrinsics& intrinsics,
                     const std::function<SE3(TimeNs)>& T_W_C, TimeNs t_ns, const RenderOptions& options,
                     cv::Mat* depth_m = nullptr);

}  // namespace vilslam::sim
