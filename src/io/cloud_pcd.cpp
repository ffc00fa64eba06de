// PCD codec: reads DATA ascii, binary and binary_compressed (FIELDS/SIZE/TYPE/COUNT in any order; x y z,
// optional intensity, ring, timestamp/time; other fields, padding `_` included, skipped), writes DATA
// binary x y z intensity.
#include <cstdint>
#include <cstring>
#include <limits>

#include "common/error.h"
#include "io/cloud_formats.h"
#include "io/lzf.h"

namespace vilslam::cloud_detail {

namespace {

struct Header {
  std::vector<std::string> fields;
  std::vector<std::size_t> sizes;
  std::vector<char> types;
  std::vector<std::size_t> counts;
  std::size_t width = 0, height = 1, points = 0;
  bool have_points = false;
  std::string data;
  std::size_t payload_begin = 0;
  long lines = 0;
};

std::size_t parse_count(const std::string& path, const std::string& word, long line) {
  char* stop = nullptr;
  const unsigned long long v = std::strtoull(word.c_str(), &stop, 10);
  if (word.empty() || *stop != '\0' || word[0] == '-') throw InputError(path, "bad header: not a count: " + word, line);
  return static_cast<std::size_t>(v);
}

Header parse_header(const std::string& path, const std::string& bytes) {
  Header h;
  std::size_t pos = 0;
  while (h.data.empty()) {
    const std::size_t end = bytes.find('\n', pos);
    if (end == std::string::npos) throw InputError(path, "bad header: no DATA line", h.lines + 1);
    const std::vector<std::string> w = split_words(bytes.substr(pos, end - pos));
    pos = end + 1;
    ++h.lines;
    if (w.empty() || w[0][0] == '#') continue;
    const std::string& key = w[0];
    const auto counts = [&]() {
      std::vector<std::size_t> v;
      for (std::size_t i = 1; i < w.size(); ++i) v.push_back(parse_count(path, w[i], h.lines));
      return v;
    };
    if (key == "VERSION" || key == "VIEWPOINT") continue;
    if (key == "FIELDS") {
      h.fields.assign(w.begin() + 1, w.end());
    } else if (key == "SIZE") {
      h.sizes = counts();
    } else if (key == "COUNT") {
      h.counts = counts();
    } else if (key == "TYPE") {
      for (std::size_t i = 1; i < w.size(); ++i) h.types.push_back(w[i].size() == 1 ? w[i][0] : '?');
    } else if (key == "WIDTH" && w.size() == 2) {
      h.width = parse_count(path, w[1], h.lines);
    } else if (key == "HEIGHT" && w.size() == 2) {
      h.height = parse_count(path, w[1], h.lines);
    } else if (key == "POINTS" && w.size() == 2) {
      h.points = parse_count(path, w[1], h.lines);
      h.have_points = true;
    } else if (key == "DATA" && w.size() == 2) {
      h.data = w[1];
    } else {
      throw InputError(path, "bad header: unexpected line starting with '" + key + "'", h.lines);
    }
  }
  if (!h.have_points) h.points = h.width * h.height;
  if (h.counts.empty()) h.counts.assign(h.fields.size(), 1);
  if (h.fields.empty() || h.sizes.size() != h.fields.size() || h.types.size() != h.fields.size() ||
      h.counts.size() != h.fields.size()) {
    throw InputError(path, "bad header: FIELDS, SIZE, TYPE and COUNT must list the same number of entries");
  }
  if (h.data != "binary" && h.data != "ascii" && h.data != "binary_compressed") {
    throw InputError(path, "bad header: unknown DATA '" + h.data + "'");
  }
  h.payload_begin = pos;
  return h;
}

Scalar pcd_scalar(const std::string& path, char type, std::size_t size) {
  if (type == 'F' && size == 4) return Scalar::kF32;
  if (type == 'F' && size == 8) return Scalar::kF64;
  if (type == 'I' && size == 1) return Scalar::kI8;
  if (type == 'I' && size == 2) return Scalar::kI16;
  if (type == 'I' && size == 4) return Scalar::kI32;
  if (type == 'U' && size == 1) return Scalar::kU8;
  if (type == 'U' && size == 2) return Scalar::kU16;
  if (type == 'U' && size == 4) return Scalar::kU32;
  throw InputError(path, std::string("bad header: unsupported field type ") + type + std::to_string(size));
}

// PCL's binary_compressed payload: uint32 compressed size, uint32 uncompressed size, then LZF data that
// holds the fields one after another (every point's first field, then every point's second field, ...).
// Returns the points as packed records, the layout of DATA binary.
std::string decompress_fields(const std::string& path, const std::string& bytes, std::size_t begin, std::size_t points,
                              const std::vector<std::size_t>& field_bytes) {
  constexpr std::size_t kSizesBytes = 2 * sizeof(std::uint32_t);
  const std::size_t available = bytes.size() - std::min(begin, bytes.size());
  if (available < kSizesBytes) throw InputError(path, "truncated binary_compressed payload: no size header");
  std::uint32_t sizes[2];
  std::memcpy(sizes, bytes.data() + begin, kSizesBytes);
  const std::size_t compressed = sizes[0], uncompressed = sizes[1];
  if (compressed > available - kSizesBytes) {
    throw InputError(path, "truncated binary_compressed payload: " + std::to_string(compressed) +
                               " compressed bytes declared, " + std::to_string(available - kSizesBytes) + " present");
  }
  std::size_t stride = 0;
  for (std::size_t b : field_bytes) stride += b;
  if (points > std::numeric_limits<std::uint32_t>::max() / stride || uncompressed != points * stride) {
    throw InputError(path, "binary_compressed payload: uncompressed size " + std::to_string(uncompressed) +
                               " bytes does not match " + std::to_string(points) + " points of " +
                               std::to_string(stride) + " bytes");
  }
  std::string by_field;
  try {
    by_field = lzf_decompress(bytes.data() + begin + kSizesBytes, compressed, uncompressed);
  } catch (const LzfError& e) {
    throw InputError(path, std::string("binary_compressed payload: ") + e.what());
  }
  std::string records(uncompressed, '\0');
  std::size_t from = 0, field_offset = 0;
  for (std::size_t width : field_bytes) {
    for (std::size_t i = 0; i < points; ++i, from += width) {
      std::memcpy(records.data() + i * stride + field_offset, by_field.data() + from, width);
    }
    field_offset += width;
  }
  return records;
}

}  // namespace

// Larger counts are not point fields (and would let a record size overflow).
constexpr std::size_t kMaxCount = 65536;

PointCloud decode_pcd(const std::string& path, const std::string& bytes) {
  const Header h = parse_header(path, bytes);
  const bool ascii = h.data == "ascii";
  RecordLayout layout;
  std::vector<std::size_t> field_bytes;
  for (std::size_t f = 0; f < h.fields.size(); ++f) {
    const std::string& name = h.fields[f];
    if (h.sizes[f] == 0 || h.sizes[f] > 8 || h.counts[f] == 0 || h.counts[f] > kMaxCount) {
      throw InputError(path, "bad header: field '" + name + "' has SIZE " + std::to_string(h.sizes[f]) + " COUNT " +
                                 std::to_string(h.counts[f]) + " (SIZE 1 to 8, COUNT 1 to 65536)");
    }
    // Types matter only for the fields we keep; the rest are skipped by their declared size.
    const Scalar type = field_slot(name) >= 0 ? pcd_scalar(path, h.types[f], h.sizes[f]) : Scalar::kU8;
    field_bytes.push_back(h.sizes[f] * h.counts[f]);
    layout.add_field(name, type, ascii ? h.counts[f] : field_bytes.back());
  }
  if (!layout.has[kX] || !layout.has[kY] || !layout.has[kZ]) throw InputError(path, "bad header: FIELDS lacks x, y or z");
  if (ascii) return decode_ascii(path, bytes, h.payload_begin, h.points, layout, h.lines + 1);
  if (h.data == "binary") return decode_binary(path, bytes, h.payload_begin, h.points, layout);
  if (h.points == 0) return {};
  return decode_binary(path, decompress_fields(path, bytes, h.payload_begin, h.points, field_bytes), 0, h.points, layout);
}

std::string encode_pcd(const PointCloud& cloud) {
  const std::string n = std::to_string(cloud.size());
  return "# .PCD v0.7 - Point Cloud Data file format\nVERSION 0.7\nFIELDS x y z intensity\nSIZE 4 4 4 4\n"
         "TYPE F F F F\nCOUNT 1 1 1 1\nWIDTH " + n + "\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS " + n +
         "\nDATA binary\n" + pack_xyzi(cloud);
}

}  // namespace vilslam::cloud_detail
