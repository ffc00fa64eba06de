// sensor_msgs/Image and CompressedImage to and from 8-bit grey images.
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "io/ros_convert.h"
#include "io/ros_wire.h"

namespace vilslam {
namespace {

int channels_of(const std::string& encoding) {
  if (encoding == "mono8") return 1;
  if (encoding == "rgb8" || encoding == "bgr8") return 3;
  throw WireError("image encoding '" + encoding + "' is not supported (mono8, rgb8, bgr8)");
}

}  // namespace

void check_ros_image(const RosImage& image) {
  const int channels = channels_of(image.encoding);
  if (image.width == 0 || image.height == 0) throw WireError("empty image");
  const std::uint64_t row_bytes = std::uint64_t{image.width} * channels;
  if (image.step < row_bytes) {
    throw WireError("image step " + std::to_string(image.step) + " < width x channels " + std::to_string(row_bytes));
  }
  if (image.data.size() != std::uint64_t{image.step} * image.height) {
    throw WireError("image data has " + std::to_string(image.data.size()) + " bytes, step x height is " +
                    std::to_string(std::uint64_t{image.step} * image.height));
  }
}

cv::Mat grey_from_ros_image(const RosImage& image) {
  check_ros_image(image);
  const int channels = channels_of(image.encoding);
  const cv::Mat view(static_cast<int>(image.height), static_cast<int>(image.width), CV_8UC(channels),
                     const_cast<std::uint8_t*>(image.data.data()), image.step);
  cv::Mat grey;
  if (channels == 1) {
    grey = view.clone();
  } else {
    cv::cvtColor(view, grey, image.encoding == "rgb8" ? cv::COLOR_RGB2GRAY : cv::COLOR_BGR2GRAY);
  }
  return grey;
}

cv::Mat grey_from_ros_compressed_image(const RosCompressedImage& image) {
  if (image.data.empty()) throw WireError("empty compressed image");
  const cv::Mat buffer(1, static_cast<int>(image.data.size()), CV_8UC1, const_cast<std::uint8_t*>(image.data.data()));
  cv::Mat grey = cv::imdecode(buffer, cv::IMREAD_GRAYSCALE);
  if (grey.empty()) throw WireError("cannot decode the compressed image (format '" + image.format + "')");
  return grey;
}

RosImage ros_image_from_grey(const cv::Mat& grey, TimeNs t_ns, const std::string& frame_id) {
  if (grey.type() != CV_8UC1) throw std::invalid_argument("ros_image_from_grey: not an 8-bit grey image");
  RosImage m;
  m.header.stamp_ns = t_ns;
  m.header.frame_id = frame_id;
  m.height = static_cast<std::uint32_t>(grey.rows);
  m.width = static_cast<std::uint32_t>(grey.cols);
  m.encoding = "mono8";
  m.step = m.width;
  m.data.resize(std::size_t{m.step} * m.height);
  for (int r = 0; r < grey.rows; ++r) std::memcpy(m.data.data() + std::size_t{m.step} * r, grey.ptr(r), m.width);
  return m;
}

}  // namespace vilslam
