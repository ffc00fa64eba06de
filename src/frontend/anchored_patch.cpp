#include "frontend/anchored_patch.h"

#include <Eigen/Cholesky>
#include <Eigen/LU>

#include <cmath>

namespace vilslam {
namespace {

// Bilinear intensity of an 8-bit image at (x, y); the caller keeps (x, y) at least one pixel inside.
double sample(const cv::Mat& image, double x, double y) {
  const int x0 = static_cast<int>(std::floor(x));
  const int y0 = static_cast<int>(std::floor(y));
  const double ax = x - x0, ay = y - y0;
  const uchar* row0 = image.ptr<uchar>(y0);
  const uchar* row1 = image.ptr<uchar>(y0 + 1);
  return (1 - ay) * ((1 - ax) * row0[x0] + ax * row0[x0 + 1]) + ay * ((1 - ax) * row1[x0] + ax * row1[x0 + 1]);
}

// Bilinear intensity and gradient at (x, y): the image and its Scharr derivatives (CV_16SC2, 32 x the
// gradient, as cv::buildOpticalFlowPyramid keeps them) share the weights.
struct Sample {
  double value, gx, gy;
};
Sample sample_with_gradient(const cv::Mat& image, const cv::Mat& derivatives, double x, double y) {
  const int x0 = static_cast<int>(std::floor(x));
  const int y0 = static_cast<int>(std::floor(y));
  const double ax = x - x0, ay = y - y0;
  const double w00 = (1 - ax) * (1 - ay), w01 = ax * (1 - ay), w10 = (1 - ax) * ay, w11 = ax * ay;
  const uchar* i0 = image.ptr<uchar>(y0) + x0;
  const uchar* i1 = image.ptr<uchar>(y0 + 1) + x0;
  const short* d0 = derivatives.ptr<short>(y0) + 2 * x0;
  const short* d1 = derivatives.ptr<short>(y0 + 1) + 2 * x0;
  constexpr double kScharr = 1.0 / 32.0;
  return {w00 * i0[0] + w01 * i0[1] + w10 * i1[0] + w11 * i1[1],
          kScharr * (w00 * d0[0] + w01 * d0[2] + w10 * d1[0] + w11 * d1[2]),
          kScharr * (w00 * d0[1] + w01 * d0[3] + w10 * d1[1] + w11 * d1[3])};
}

// True when every sample of the warped patch (and its bilinear neighbours) lies inside the image.
bool warp_inside(const cv::Mat& image, const Eigen::Vector2d& c, const Eigen::Matrix2d& A, int h) {
  for (const double sx : {-1.0, 1.0}) {
    for (const double sy : {-1.0, 1.0}) {
      const Eigen::Vector2d q = c + A * Eigen::Vector2d(sx * h, sy * h);
      if (q.x() < 2 || q.y() < 2 || q.x() > image.cols - 3 || q.y() > image.rows - 3) return false;
    }
  }
  return true;
}

// Zero-mean normalized correlation of two equally long sample lists.
double correlation(const std::vector<float>& a, const std::vector<double>& b) {
  const double n = static_cast<double>(a.size());
  double ma = 0, mb = 0;
  for (std::size_t k = 0; k < a.size(); ++k) {
    ma += a[k];
    mb += b[k];
  }
  ma /= n;
  mb /= n;
  double ab = 0, aa = 0, bb = 0;
  for (std::size_t k = 0; k < a.size(); ++k) {
    ab += (a[k] - ma) * (b[k] - mb);
    aa += (a[k] - ma) * (a[k] - ma);
    bb += (b[k] - mb) * (b[k] - mb);
  }
  return aa > 0 && bb > 0 ? ab / std::sqrt(aa * bb) : 0.0;
}

}  // namespace

bool make_anchor(const cv::Mat& image, const Eigen::Vector2d& px, int half_px, PatchAnchor* anchor) {
  if (!warp_inside(image, px, Eigen::Matrix2d::Identity(), half_px)) return false;
  anchor->half_px = half_px;
  anchor->A.setIdentity();
  anchor->gain = 1.0;
  anchor->bias = 0.0;
  anchor->patch.clear();
  for (int dy = -half_px; dy <= half_px; ++dy) {
    for (int dx = -half_px; dx <= half_px; ++dx) {
      anchor->patch.push_back(static_cast<float>(sample(image, px.x() + dx, px.y() + dy)));
    }
  }
  return true;
}

bool refine_to_anchor(const cv::Mat& image, const cv::Mat& derivatives, const AnchorRefinementConfig& config,
                      Eigen::Vector2d* px, PatchAnchor* anchor) {
  using Vec8 = Eigen::Matrix<double, 8, 1>;
  using Mat8 = Eigen::Matrix<double, 8, 8>;
  const int h = anchor->half_px;
  Eigen::Vector2d c = *px;
  Eigen::Matrix2d A = anchor->A;
  double gain = anchor->gain, bias = anchor->bias;
  // A chord method: the normal matrix is formed only every kNormalEvery iterations, and the first iteration
  // reuses the one of the track's previous step when there is one. The patch changes little from one image to
  // the next, and the fixed point, where the current Jacobian is orthogonal to the residual, stays the same.
  constexpr int kNormalEvery = 4;
  Mat8 normal = anchor->normal;
  bool have_normal = anchor->has_normal;
  Eigen::LDLT<Mat8> ldlt;
  if (have_normal) ldlt.compute(normal);
  std::vector<double> warped(anchor->patch.size());  // the samples of the last iteration
  bool converged = false;
  for (int iteration = 0; iteration < config.max_iterations && !converged; ++iteration) {
    if (!warp_inside(image, c, A, h)) return false;
    const bool form_normal = iteration % kNormalEvery == 0 && (iteration > 0 || !have_normal);
    Mat8 H = Mat8::Zero();
    Vec8 g = Vec8::Zero();
    std::size_t k = 0;
    for (int dy = -h; dy <= h; ++dy) {
      for (int dx = -h; dx <= h; ++dx, ++k) {
        const Eigen::Vector2d q = c + A * Eigen::Vector2d(dx, dy);
        const Sample s = sample_with_gradient(image, derivatives, q.x(), q.y());
        const double T = anchor->patch[k];
        warped[k] = s.value;
        const double r = s.value - (gain * T + bias);
        // d r / d [c_x, c_y, A00, A01, A10, A11, gain, bias] of r = I(c + A x) - gain T - bias.
        Vec8 J;
        J << s.gx, s.gy, s.gx * dx, s.gx * dy, s.gy * dx, s.gy * dy, -T, -1.0;
        if (form_normal) H.noalias() += J * J.transpose();
        g += J * r;
      }
    }
    if (form_normal) {
      normal = H;
      have_normal = true;
      ldlt.compute(normal);
    }
    if (ldlt.info() != Eigen::Success) return false;
    const Vec8 step = -ldlt.solve(g);
    if (!step.allFinite()) return false;
    c += step.head<2>();
    A(0, 0) += step(2);
    A(0, 1) += step(3);
    A(1, 0) += step(4);
    A(1, 1) += step(5);
    gain += step(6);
    bias += step(7);
    // The position decides: in faint texture the affine part stays loose and may still move a little.
    converged = step.head<2>().norm() < 0.01;
  }
  if (!converged || !warp_inside(image, c, A, h) || (c - *px).norm() > config.max_correction_px) return false;
  const double det = A.determinant();
  if (!(det > 0) || std::sqrt(det) < config.min_scale || std::sqrt(det) > config.max_scale) return false;
  // The last iteration's samples, less than 0.01 px from the final position.
  if (correlation(anchor->patch, warped) < config.min_correlation) return false;
  *px = c;
  anchor->A = A;
  anchor->gain = gain;
  anchor->bias = bias;
  anchor->normal = normal;
  anchor->has_normal = true;
  return true;
}

}  // namespace vilslam
