#pragma once
// Internal to the io module: the pieces shared by the PLY and PCD codecs of cloud_io.cpp.
#include <cstddef>
#include <string>
#include <vector>

#include "io/cloud_io.h"

namespace vilslam::cloud_detail {

// A scalar type as both PLY and PCD headers declare them (all stored little-endian).
enum class Scalar { kI8, kU8, kI16, kU16, kI32, kU32, kF32, kF64 };

std::size_t scalar_size(Scalar type);
// Reads one little-endian scalar of the given type at p, widened to double.
double load_scalar(const char* p, Scalar type);

// Splits a header line into whitespace-separated tokens.
std::vector<std::string> split_words(const std::string& line);

// The per-point fields a cloud file can fill, in PointCloud's order.
enum Slot : int { kX, kY, kZ, kIntensity, kRing, kTime, kNumSlots };

// The slot a field named `name` fills, or -1: x, y, z; intensity (also PLY's scalar_intensity); ring;
// timestamp or time (seconds, PCL / Velodyne drivers).
int field_slot(const std::string& name);

// Where the fields sit inside one record (byte offsets for binary, token indices for ASCII).
struct RecordLayout {
  std::size_t stride = 0;  // bytes (binary) or tokens (ASCII) per record
  std::size_t offset[kNumSlots] = {};
  Scalar type[kNumSlots] = {Scalar::kF32, Scalar::kF32, Scalar::kF32, Scalar::kF32, Scalar::kF32, Scalar::kF32};
  bool has[kNumSlots] = {};
  // Appends a field `width` bytes (binary) or tokens (ASCII) wide; the first field of each slot's name fills
  // the slot (with COUNT > 1, its first element).
  void add_field(const std::string& name, Scalar type, std::size_t width);
};

// Decodes `count` packed little-endian records starting at bytes[begin]; throws when the payload is short.
PointCloud decode_binary(const std::string& path, const std::string& bytes, std::size_t begin, std::size_t count,
                         const RecordLayout& layout);
// Decodes `count` ASCII records, one per line, starting at bytes[begin]; first_line numbers the first record.
PointCloud decode_ascii(const std::string& path, const std::string& bytes, std::size_t begin, std::size_t count,
                        const RecordLayout& layout, long first_line);

// Packs the cloud as little-endian float32 records x y z intensity (intensity 0 when the cloud has none).
std::string pack_xyzi(const PointCloud& cloud);

PointCloud decode_ply(const std::string& path, const std::string& bytes);
PointCloud decode_pcd(const std::string& path, const std::string& bytes);
std::string encode_ply(const PointCloud& cloud);
std::string encode_pcd(const PointCloud& cloud);

}  // namespace vilslam::cloud_detail
