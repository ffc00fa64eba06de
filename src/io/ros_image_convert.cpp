// sensor_msgs/Image and CompressedImage to and from 8-bit grey images.
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <array>
#include <cstring>
#include <stdexcept>

#include "io/ros_convert.h"
#include "io/ros_wire.h"

namespace vilslam {
namespace {

enum class Layout { kMono, kRgb, kBgr, kRgba, kBgra, kBayer };

struct Encoding {
  const char* name;
  Layout layout;
  int channels;
  int bytes_per_channel;
  int bayer_to_grey;  // cv::COLOR_Bayer*2GRAY for Bayer layouts
};

// OpenCV names a Bayer pattern by the second row's second and third pixels, ROS by the first 2x2 block, so
// ROS's rggb is OpenCV's BG (as cv_bridge maps them; tests/io/test_ros_image_convert.cpp mosaics a colour
// image each way and checks the grey it demosaics to).
constexpr std::array<Encoding, 16> kEncodings{{
    {"mono8", Layout::kMono, 1, 1, 0},
    {"8UC1", Layout::kMono, 1, 1, 0},
    {"mono16", Layout::kMono, 1, 2, 0},
    {"16UC1", Layout::kMono, 1, 2, 0},
    {"rgb8", Layout::kRgb, 3, 1, 0},
    {"bgr8", Layout::kBgr, 3, 1, 0},
    {"rgba8", Layout::kRgba, 4, 1, 0},
    {"bgra8", Layout::kBgra, 4, 1, 0},
    {"bayer_rggb8", Layout::kBayer, 1, 1, cv::COLOR_BayerBG2GRAY},
    {"bayer_bggr8", Layout::kBayer, 1, 1, cv::COLOR_BayerRG2GRAY},
    {"bayer_gbrg8", Layout::kBayer, 1, 1, cv::COLOR_BayerGR2GRAY},
    {"bayer_grbg8", Layout::kBayer, 1, 1, cv::COLOR_BayerGB2GRAY},
    {"bayer_rggb16", Layout::kBayer, 1, 2, cv::COLOR_BayerBG2GRAY},
    {"bayer_bggr16", Layout::kBayer, 1, 2, cv::COLOR_BayerRG2GRAY},
    {"bayer_gbrg16", Layout::kBayer, 1, 2, cv::COLOR_BayerGR2GRAY},
    {"bayer_grbg16", Layout::kBayer, 1, 2, cv::COLOR_BayerGB2GRAY},
}};

const Encoding& encoding_of(const std::string& name) {
  for (const Encoding& e : kEncodings) {
    if (name == e.name) return e;
  }
  std::string names;
  for (const Encoding& e : kEncodings) names += std::string(names.empty() ? "" : ", ") + e.name;
  throw WireError("image encoding '" + name + "' is not supported (" + names + ")");
}

// The message's pixels as a matrix of its own depth (16-bit samples in host order).
cv::Mat pixels_of(const RosImage& image, const Encoding& e) {
  const int type = CV_MAKETYPE(e.bytes_per_channel == 1 ? CV_8U : CV_16U, e.channels);
  const cv::Mat view(static_cast<int>(image.height), static_cast<int>(image.width), type,
                     const_cast<std::uint8_t*>(image.data.data()), image.step);
  cv::Mat pixels = view.clone();
  if (e.bytes_per_channel == 2 && image.is_bigendian) {
    for (int r = 0; r < pixels.rows; ++r) {
      auto* row = pixels.ptr<std::uint16_t>(r);
      for (int c = 0; c < pixels.cols * e.channels; ++c) row[c] = static_cast<std::uint16_t>((row[c] >> 8) | (row[c] << 8));
    }
  }
  return pixels;
}

}  // namespace

void check_ros_image(const RosImage& image) {
  const Encoding& e = encoding_of(image.encoding);
  if (image.width == 0 || image.height == 0) throw WireError("empty image");
  const std::uint64_t row_bytes = std::uint64_t{image.width} * e.channels * e.bytes_per_channel;
  if (image.step < row_bytes) {
    throw WireError("image step " + std::to_string(image.step) + " < width x bytes per pixel " + std::to_string(row_bytes));
  }
  if (e.bytes_per_channel == 2 && image.step % 2 != 0) throw WireError("16-bit image with an odd step " + std::to_string(image.step));
  if (e.layout == Layout::kBayer && (image.width < 2 || image.height < 2)) throw WireError("Bayer image smaller than 2x2");
  if (image.data.size() != std::uint64_t{image.step} * image.height) {
    throw WireError("image data has " + std::to_string(image.data.size()) + " bytes, step x height is " +
                    std::to_string(std::uint64_t{image.step} * image.height));
  }
}

int ros_image_significant_bits(const RosImage& image) {
  check_ros_image(image);
  const Encoding& e = encoding_of(image.encoding);
  if (e.bytes_per_channel == 1) return 0;
  double max_value = 0.0;
  cv::minMaxLoc(pixels_of(image, e).reshape(1), nullptr, &max_value);
  int bits = 8;
  while (bits < 16 && max_value >= static_cast<double>(1 << bits)) ++bits;
  return bits;
}

cv::Mat grey_from_ros_image(const RosImage& image, int significant_bits) {
  check_ros_image(image);
  if (significant_bits < 8 || significant_bits > 16) {
    throw std::invalid_argument("grey_from_ros_image: significant bits must be 8 to 16, got " + std::to_string(significant_bits));
  }
  const Encoding& e = encoding_of(image.encoding);
  cv::Mat pixels = pixels_of(image, e);
  if (e.bytes_per_channel == 2) {
    // Full scale of the significant bits to 255, rounded and saturated (a sample above it clips).
    cv::Mat eight;
    pixels.convertTo(eight, CV_MAKETYPE(CV_8U, e.channels), 255.0 / ((1 << significant_bits) - 1));
    pixels = eight;
  }
  cv::Mat grey;
  switch (e.layout) {
    case Layout::kMono: return pixels;
    case Layout::kRgb: cv::cvtColor(pixels, grey, cv::COLOR_RGB2GRAY); break;
    case Layout::kBgr: cv::cvtColor(pixels, grey, cv::COLOR_BGR2GRAY); break;
    case Layout::kRgba: cv::cvtColor(pixels, grey, cv::COLOR_RGBA2GRAY); break;
    case Layout::kBgra: cv::cvtColor(pixels, grey, cv::COLOR_BGRA2GRAY); break;
    case Layout::kBayer: cv::cvtColor(pixels, grey, e.bayer_to_grey); break;
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
