#pragma once
// Figures for the docs: top views of point clouds (coloured by height) with routes drawn on them.
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <opencv2/core.hpp>

#include "common/lie.h"

namespace vilslam::sim {

// A white canvas over a rectangle of the x-y plane (x to the right, y up), square pixels.
class TopView {
 public:
  // The longer side of extent_xy (metres) spans max_side_px pixels.
  TopView(const Eigen::AlignedBox2d& extent_xy, int max_side_px);

  // Each pixel shows its highest point with z <= z_clip (a cut through the ceiling), coloured by height
  // from z_min (blue) to z_max (red); a point covers dot_px x dot_px pixels. Pixels whose points span
  // less than min_span_m in height stay blank (with min_span_m > 0, floors and ground drop out and walls,
  // shelves and trees remain, even on sloped ground). Later calls draw on top.
  void draw_points(const std::vector<Eigen::Vector3f>& points, double z_min, double z_max, double z_clip,
                   int dot_px = 1, double min_span_m = 0);
  // A polyline through the points' x-y (BGR colour), with a dot at the first point.
  void draw_path(const std::vector<Vec3>& points, const cv::Scalar& bgr, int thickness_px);
  // A scale bar of a round length in the lower left corner.
  void draw_scale_bar();

  // Pixel of an x-y position (column, row).
  cv::Point2d pixel(double x, double y) const;
  double metres_per_px() const { return metres_per_px_; }
  const cv::Mat& image() const { return image_; }

 private:
  Eigen::AlignedBox2d extent_;
  double metres_per_px_;
  cv::Mat image_;  // CV_8UC3
};

// Writes an image as PNG through a temporary file and a rename (never a half-written file).
// Throws InputError(path, ...) when it cannot be written.
void write_png(const std::string& path, const cv::Mat& image);

}  // namespace vilslam::sim
