#include "sim/figures.h"

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>

#include "common/error.h"

namespace vilslam::sim {

TopView::TopView(const Eigen::AlignedBox2d& extent_xy, int max_side_px) : extent_(extent_xy) {
  const Eigen::Vector2d size = extent_xy.sizes();
  if (!(size.minCoeff() > 0) || max_side_px < 2) throw std::invalid_argument("TopView needs a non-empty extent");
  metres_per_px_ = size.maxCoeff() / max_side_px;
  const int cols = std::max(2, static_cast<int>(std::ceil(size.x() / metres_per_px_)));
  const int rows = std::max(2, static_cast<int>(std::ceil(size.y() / metres_per_px_)));
  image_ = cv::Mat(rows, cols, CV_8UC3, cv::Scalar(255, 255, 255));
}

cv::Point2d TopView::pixel(double x, double y) const {
  return {(x - extent_.min().x()) / metres_per_px_, (extent_.max().y() - y) / metres_per_px_};
}

void TopView::draw_points(const std::vector<Eigen::Vector3f>& points, double z_min, double z_max, double z_clip,
                          int dot_px, double min_span_m) {
  constexpr float kInf = std::numeric_limits<float>::infinity();
  cv::Mat top_z(image_.size(), CV_32F, cv::Scalar(-kInf)), bottom_z(image_.size(), CV_32F, cv::Scalar(kInf));
  for (const Eigen::Vector3f& p : points) {
    if (p.z() > z_clip) continue;
    const cv::Point2d px = pixel(p.x(), p.y());
    const int c0 = static_cast<int>(std::floor(px.x)) - (dot_px - 1) / 2;
    const int r0 = static_cast<int>(std::floor(px.y)) - (dot_px - 1) / 2;
    for (int r = std::max(r0, 0); r < std::min(r0 + dot_px, image_.rows); ++r) {
      for (int c = std::max(c0, 0); c < std::min(c0 + dot_px, image_.cols); ++c) {
        top_z.at<float>(r, c) = std::max(top_z.at<float>(r, c), p.z());
        bottom_z.at<float>(r, c) = std::min(bottom_z.at<float>(r, c), p.z());
      }
    }
  }
  cv::Mat level(image_.size(), CV_8U);
  const double z_range = std::max(z_max - z_min, 1e-6);
  for (int r = 0; r < image_.rows; ++r) {
    for (int c = 0; c < image_.cols; ++c) {
      const double t = std::clamp((top_z.at<float>(r, c) - z_min) / z_range, 0.0, 1.0);
      level.at<std::uint8_t>(r, c) = static_cast<std::uint8_t>(std::lround(255 * t));
    }
  }
  cv::Mat colour;
  cv::applyColorMap(level, colour, cv::COLORMAP_TURBO);
  const cv::Mat height_span = top_z - bottom_z;
  colour.copyTo(image_, (top_z > -kInf) & (height_span >= static_cast<float>(min_span_m)));
}

void TopView::draw_path(const std::vector<Vec3>& points, const cv::Scalar& bgr, int thickness_px) {
  if (points.empty()) return;
  constexpr int kShift = 4;  // sub-pixel precision of the drawing
  auto fixed = [&](const Vec3& p) {
    const cv::Point2d px = pixel(p.x(), p.y());
    return cv::Point(static_cast<int>(std::lround(px.x * (1 << kShift))), static_cast<int>(std::lround(px.y * (1 << kShift))));
  };
  std::vector<cv::Point> line;
  for (const Vec3& p : points) line.push_back(fixed(p));
  cv::polylines(image_, line, false, bgr, thickness_px, cv::LINE_AA, kShift);
  cv::circle(image_, line.front(), (3 * thickness_px) << kShift, bgr, cv::FILLED, cv::LINE_AA, kShift);
}

void TopView::draw_scale_bar() {
  const double target_m = 0.2 * image_.cols * metres_per_px_;
  const double decade = std::pow(10.0, std::floor(std::log10(target_m)));
  const double bar_m = target_m >= 5 * decade ? 5 * decade : target_m >= 2 * decade ? 2 * decade : decade;
  const int length_px = static_cast<int>(std::lround(bar_m / metres_per_px_));
  const cv::Point start(10, image_.rows - 12);
  cv::line(image_, start, start + cv::Point(length_px, 0), cv::Scalar(0, 0, 0), 2);
  char label[32];
  std::snprintf(label, sizeof label, "%g m", bar_m);
  cv::putText(image_, label, start + cv::Point(length_px + 6, 5), cv::FONT_HERSHEY_SIMPLEX, 0.45, cv::Scalar(0, 0, 0), 1,
              cv::LINE_AA);
}

void write_png(const std::string& path, const cv::Mat& image) {
  const std::filesystem::path target(path);
  const std::filesystem::path temp = target.parent_path() / ("." + target.filename().string() + ".tmp.png");
  std::string problem;
  try {
    if (!cv::imwrite(temp.string(), image, {cv::IMWRITE_PNG_COMPRESSION, 9})) problem = "cannot write PNG";
  } catch (const cv::Exception& e) {
    problem = std::string("cannot write PNG: ") + e.what();
  }
  std::error_code ec;
  if (problem.empty()) {
    std::filesystem::rename(temp, target, ec);
    if (ec) problem = "cannot rename the written PNG: " + ec.message();
  }
  if (!problem.empty()) {
    std::filesystem::remove(temp, ec);
    throw InputError(path, problem);
  }
}

}  // namespace vilslam::sim
